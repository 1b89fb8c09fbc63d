// A square block of particles on a flat, frictionless bed, and a uniform radial velocity for it: the
// scene of the particles' energy tests (test_particle_energy.cpp) and of the thickness test
// (test_particle_thickness.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"

namespace talus::test {

/// A block 1 m thick over cells [lo, hi)^2 of an n x n flat, frictionless bed (delta = 0), elastic
/// throughout (c = 1e9 Pa, phi = 30 degrees), density rho.
struct FlatParticleBlock {
  Grid grid;
  particles::ParticleTerrain terrain;
  particles::SeededParticles seeded;
  particles::ParticleMaterial material;
};

FlatParticleBlock flatParticleBlock(int n, double dx, int lo, int hi, double rho, double particlesPerCell);

/// Gives the solver's particles the uniform radial velocity v = rate (x - x_c) about (x_c, x_c), from
/// their seeded positions; returns its kinetic energy [J].
double setRadialVelocity(particles::ParticleSolver& solver, const particles::SeededParticles& seeded, double rate,
                         double xc);

}  // namespace talus::test

#include "render/ShaderResources.hpp"

#include <stdexcept>

// Resources of a static library must be registered by hand (outside any namespace).
static void registerShaderResources() {
  static const bool done = [] {
    Q_INIT_RESOURCE(shaders);
    return true;
  }();
  (void)done;
}

namespace talus::gui {

std::unique_ptr<QOpenGLShaderProgram> loadShaderProgram(const QString& name) {
  registerShaderResources();
  auto program = std::make_unique<QOpenGLShaderProgram>();
  const QString base = ":/shaders/" + name;
  if (!program->addShaderFromSourceFile(QOpenGLShader::Vertex, base + ".vert.glsl") ||
      !program->addShaderFromSourceFile(QOpenGLShader::Fragment, base + ".frag.glsl") || !program->link())
    throw std::runtime_error("shader program '" + name.toStdString() + "': " + program->log().toStdString());
  return program;
}

}  // namespace talus::gui

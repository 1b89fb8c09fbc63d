// The GLSL files of shaders/, embedded as Qt resources under ":/shaders/".
#pragma once
#include <QOpenGLShaderProgram>
#include <QString>
#include <memory>

namespace talus::gui {

/// Compiles and links shaders/<name>.vert.glsl and shaders/<name>.frag.glsl. Throws
/// std::runtime_error with the compiler log on failure. Needs a current GL context.
std::unique_ptr<QOpenGLShaderProgram> loadShaderProgram(const QString& name);

}  // namespace talus::gui

#pragma once
// Private: the check the GL warps run before writing a cell into a layer of a 2-D array texture.

#include <stdexcept>
#include <string>

#include <glad/gl.h>

namespace throng::detail {

/// Throws std::invalid_argument, starting with `who`, when layer `layer` of the 2-D array texture
/// `target` does not exist or is smaller than `size` pixels square (binds `target`).
inline void checkLayerFits(const GladGLContext& gl, GLuint target, int layer, int size, const std::string& who) {
    GLint width = 0, height = 0, layers = 0;
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, target);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D_ARRAY, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D_ARRAY, 0, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D_ARRAY, 0, GL_TEXTURE_DEPTH, &layers);
    if (layer < 0 || layer >= layers || size > width || size > height)
        throw std::invalid_argument(who + ": layer " + std::to_string(layer) + " of " + std::to_string(size) + " pixels does not fit the target (" +
                                    std::to_string(width) + "x" + std::to_string(height) + ", " + std::to_string(layers) + " layers)");
}

}  // namespace throng::detail

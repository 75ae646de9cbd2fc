#pragma once
// Private: GLSL sources of the renderer and of the transform-feedback skinner. One vertex shader
// text serves both, so that the skinning the tests read back is the skinning the renderer draws.

#include <string>

namespace throng::detail {

/// Attribute locations shared by the shaders, the mesh upload and the renderer.
enum AttributeLocation : unsigned {
    kPosition = 0, kNormal = 1, kTexcoord = 2, kJoints0 = 3, kWeights0 = 4, kJoints1 = 5, kWeights1 = 6,
    kModel = 7,  // a mat4: locations 7-10
    kTint = 11, kPaletteBase = 12
};

/// Texture units.
enum TextureUnit : int { kBaseColorUnit = 0, kPaletteUnit = 1 };

/// The vertex shader for `influences` (0, 4 or 8) joint influences. With `feedback`, it outputs
/// the skinned model-space position and normal (tfPosition, tfNormal) instead of drawing.
std::string vertexShaderSource(int influences, bool feedback);

/// The vertex shader of constant faces (rigid, back faces culled): it computes the whole shaded
/// colour of the fragment shader's formula once per vertex (texture read at level 0, as the
/// fragment shader does where texture coordinates do not vary) and passes it flat.
std::string constantFaceVertexShaderSource();

/// The fragment shader of constant faces: writes the colour its vertex shader computed.
std::string constantFaceFragmentShaderSource();

/// The vertex shader of flat-lit faces (one normal at the three vertices, texture coordinates
/// that vary; rigid, back faces culled): the light is computed once per vertex and passed flat.
std::string flatLightVertexShaderSource();

/// The fragment shader of flat-lit faces: texture, the flat light, sRGB encoding.
std::string flatLightFragmentShaderSource();

/// The shading fragment shader: base colour x texture x tint, hemisphere + sun light, sRGB output.
std::string fragmentShaderSource();

}  // namespace throng::detail

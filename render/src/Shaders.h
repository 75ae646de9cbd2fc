#pragma once
// Private: GLSL sources of the renderer and of the transform-feedback skinner. One vertex shader
// text serves both, so that the skinning the tests read back is the skinning the renderer draws.

#include <string>

namespace throng::detail {

/// Attribute locations shared by the shaders, the mesh upload and the renderer.
enum AttributeLocation : unsigned {
    kPosition = 0, kNormal = 1, kTexcoord = 2, kJoints0 = 3, kWeights0 = 4, kJoints1 = 5, kWeights1 = 6,
    kModel = 7,  // a mat4: locations 7-10
    kTint = 11,
    // An ivec3: first palette matrix (key-pose: row 0's first texel), then row 1's first texel and
    // row 1's weight's bits, or (meshes with morph targets) the first morph weight and their count.
    kPalette = 12,
    kLook = 13,     // a uvec4: the actor's colour per body region (BodyLook)
    kRegion = 14    // per vertex: its body region, 0 (none) when the mesh has none
};

/// Texture units.
enum TextureUnit : int { kBaseColorUnit = 0, kPaletteUnit = 1, kKeyPoseUnit = 2, kMorphOffsetUnit = 3, kMorphWeightUnit = 4 };

/// Texels of one vertex of one morph target in a mesh's offset buffer (RGBA32F): the position
/// offset, then the normal offset. Target k's vertex v starts at texel 2 * (k * vertices + v).
inline constexpr int kMorphTexelsPerVertex = 2;

/// Bytes of one vertex in a key-pose cache: RGBA32UI, the skinned position's exact float bits in
/// the first three words, the unit normal octahedron-encoded as two 16-bit snorms in the fourth
/// (x in the low half). One texel fetch reads a whole vertex.
inline constexpr unsigned kKeyPoseVertexBytes = 16;

/// GLSL linearToSrgb(vec3): linear RGB (clamped) to sRGB, as every shading path writes it.
std::string srgbEncodeGlsl();

/// GLSL functions of crowd diversity: srgbToLinear(vec3), lookColour(uint) decodes a packed BodyLook colour to linear
/// RGB (alpha in .a), recolour(albedo, region, look) applies an actor's look to a linear albedo
/// (BodyLook's formula), regionPaint(regions, uvLayer, look) the colour an impostor's region map
/// asks for at a texel (white for none), wearLook(blend, paint) an impostor's blended cells wearing
/// it. Needs linearToSrgb (srgbEncodeGlsl) before it. Shared by the mesh shaders and the impostor passes.
std::string bodyLookGlsl();

/// The vertex shader for `influences` (0, 4 or 8) joint influences. With `feedback`, it outputs
/// the skinned model-space position and normal (tfPosition, tfNormal) instead of drawing, with the
/// palette starting at matrix uFeedbackBase + gl_InstanceID * uFeedbackStride (uniforms; 0 unless
/// set). With `morph`, the mesh's morph targets are added before skinning: the instance's
/// weights are (target, weight) pairs in uMorphWeights (RG32F) from its first morph weight on,
/// the offsets in uMorphOffsets (see kMorphTexelsPerVertex), the mesh's vertex count in
/// uMorphVertices.
std::string vertexShaderSource(int influences, bool feedback, bool morph = false);

/// The transform-feedback program that fills key-pose cache rows: the feedback variant of
/// vertexShaderSource(influences, true) (the same skinning), capturing each vertex packed as
/// kKeyPoseVertexBytes in `tfCache` (a uvec4). Instance k of a draw skins with the palette at
/// uFeedbackBase + k * uFeedbackStride.
std::string keyPoseFillVertexShaderSource(int influences);

/// The vertex shader of key-pose items: position and normal read from the key-pose cache (texture
/// buffer uKeyPoses, texel iPaletteBase + gl_VertexID), or with `interpolative` blended with
/// texel iKeyPoseRow1 + gl_VertexID by iKeyPoseBlend (normal renormalised); then as the rigid
/// shader (same outputs for fragmentShaderSource()).
std::string keyPoseVertexShaderSource(bool interpolative);

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

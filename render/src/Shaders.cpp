#include "Shaders.h"

namespace throng::detail {
namespace {

// The palette is a texture buffer (RGBA32F, one matrix = 4 texels, columns in order): on llvmpipe a
// texel fetch is cheaper than indexing a large uniform block, and its size is not limited to 64 KiB.
constexpr const char* kVertexBody = R"GLSL(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aTexcoord;
layout(location = 3) in uvec4 aJoints0;
layout(location = 4) in vec4 aWeights0;
layout(location = 5) in uvec4 aJoints1;
layout(location = 6) in vec4 aWeights1;
layout(location = 7) in mat4 iModel;      // model matrix relative to the eye
layout(location = 11) in vec4 iTint;
// First matrix of this instance's palette (key-pose: first texel of row 0), first texel of row 1,
// and the bits of row 1's weight.
layout(location = 12) in ivec3 iPalette;
layout(location = 13) in uvec4 iLook;    // the actor's colour per body region (BodyLook)
layout(location = 14) in float aRegion;  // the vertex's body region (0: none)
#define iPaletteBase iPalette.x
#define iKeyPoseRow1 iPalette.y
#define iKeyPoseBlend intBitsToFloat(iPalette.z)
#define iMorphFirst iPalette.y
#define iMorphCount iPalette.z

uniform samplerBuffer uPalette;
uniform mat4 uViewRotation;  // the view without its translation: the eye is the origin
uniform mat4 uProjection;

#if FEEDBACK
uniform int uFeedbackBase;    // first matrix of instance 0's palette
uniform int uFeedbackStride;  // matrices from one instance's palette to the next
#if KEYPOSE_FILL
flat out uvec4 tfCache;       // one key-pose cache vertex (see packNormal)
#else
out vec3 tfPosition;
out vec3 tfNormal;
#endif
#elif CONSTANT_FACES || FLAT_LIGHT
#if CONSTANT_FACES
flat out vec4 vColor;
uniform sampler2D uTexture;
uniform bool uHasTexture;
#else
out vec2 vTexcoord;
flat out vec4 vBase;
flat out vec3 vLight;
#endif
uniform vec4 uBaseColor;
uniform vec3 uLightDirection;
uniform vec3 uLightColor;
uniform vec3 uSkyColor;
uniform vec3 uGroundColor;
#else
out vec3 vRelPosition;
out vec3 vNormal;
out vec2 vTexcoord;
flat out vec4 vTint;  // one per instance: not interpolated, so an ID render reads back exactly
out vec4 vRegion;     // one-hot body region (skin, hair, top, bottom), blended across triangles
flat out uvec4 vLook;
#endif

#if CONSTANT_FACES
SRGB_ENCODE
#endif

#if KEYPOSE_FILL || KEYPOSE
// Key-pose cache vertices: the position's float bits as they are (exact), the unit normal
// octahedron-encoded (the octahedron |x|+|y|+|z| = 1 unfolded onto a square) as two 16-bit snorms,
// a direction error below 1e-4 rad, far under what shading at 8 bits per channel can show.
uint snorm16(float v) { return uint(int(round(clamp(v, -1.0, 1.0) * 32767.0))) & 0xffffu; }
float unsnorm16(uint w) { return float(int(w << 16) >> 16) / 32767.0; }  // arithmetic shift: sign kept
uint packNormal(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    if (l1 == 0.0) return 0u;  // a mesh without normals: never read
    vec2 e = n.xy / l1;
    if (n.z < 0.0) e = (1.0 - abs(e.yx)) * vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
    return snorm16(e.x) | (snorm16(e.y) << 16);
}
vec3 unpackNormal(uint w) {
    vec2 e = vec2(unsnorm16(w), unsnorm16(w >> 16));
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    float t = max(-n.z, 0.0);
    n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
    return normalize(n);
}
#endif

#if KEYPOSE
uniform usamplerBuffer uKeyPoses;  // the cache: one texel per vertex, one row per key-pose
void cachedVertex(int first, out vec3 p, out vec3 n) {
    uvec4 t = texelFetch(uKeyPoses, first + gl_VertexID);
    p = uintBitsToFloat(t.xyz);
    n = unpackNormal(t.w);
}
#endif

#if MORPH
uniform samplerBuffer uMorphOffsets;  // the mesh's: per target and vertex, position then normal offset
uniform samplerBuffer uMorphWeights;  // this draw's: (target, weight) per non-zero weight
uniform int uMorphVertices;
// The instance's morph targets added, target by target in ascending order (as applyMorphTargets).
void morph(inout vec3 p, inout vec3 n) {
    for (int i = 0; i < iMorphCount; ++i) {
        vec2 e = texelFetch(uMorphWeights, iMorphFirst + i).xy;
        int t = 2 * (int(e.x) * uMorphVertices + gl_VertexID);
        p += e.y * texelFetch(uMorphOffsets, t).xyz;
        n += e.y * texelFetch(uMorphOffsets, t + 1).xyz;
    }
}
#endif

mat4 joint(int base, uint j) {
    int t = 4 * (base + int(j));
    return mat4(texelFetch(uPalette, t), texelFetch(uPalette, t + 1), texelFetch(uPalette, t + 2),
                texelFetch(uPalette, t + 3));
}

#if INFLUENCES > 0
// Weights arrive normalised (all zero when they summed to zero: the vertex stays in bind pose).
mat4 skinMatrix(int base) {
#if INFLUENCES == 8
    if (aWeights0 == vec4(0.0) && aWeights1 == vec4(0.0)) return mat4(1.0);
#else
    if (aWeights0 == vec4(0.0)) return mat4(1.0);
#endif
    mat4 s = joint(base, aJoints0.x) * aWeights0.x + joint(base, aJoints0.y) * aWeights0.y
           + joint(base, aJoints0.z) * aWeights0.z + joint(base, aJoints0.w) * aWeights0.w;
#if INFLUENCES == 8
    s = s + joint(base, aJoints1.x) * aWeights1.x + joint(base, aJoints1.y) * aWeights1.y
          + joint(base, aJoints1.z) * aWeights1.z + joint(base, aJoints1.w) * aWeights1.w;
#endif
    return s;
}
#endif

void main() {
    vec3 p = aPosition;
    vec3 n = aNormal;
#if MORPH
    morph(p, n);  // before skinning: offsets are in the mesh's bind frame
#endif
#if INFLUENCES > 0
#if FEEDBACK
    mat4 s = skinMatrix(uFeedbackBase + gl_InstanceID * uFeedbackStride);
#else
    mat4 s = skinMatrix(iPaletteBase);
#endif
    p = (s * vec4(p, 1.0)).xyz;  // palettes are affine: the bottom row is ignored
    n = mat3(s) * n;
#endif
#if KEYPOSE
    cachedVertex(iPaletteBase, p, n);
#if KEYPOSE == 2
    vec3 p1, n1;
    cachedVertex(iKeyPoseRow1, p1, n1);
    p = mix(p, p1, iKeyPoseBlend);
    n = mix(n, n1, iKeyPoseBlend);
    float nl = length(n);
    n = nl > 0.0 ? n / nl : n1;  // opposite normals blended half-way: take row 1's
#endif
#endif
#if FEEDBACK
    float len = length(n);
#if KEYPOSE_FILL
    tfCache = uvec4(floatBitsToUint(p), packNormal(len > 0.0 ? n / len : n));
#else
    tfPosition = p;
    tfNormal = len > 0.0 ? n / len : n;
#endif
#else
    vec4 rel = iModel * vec4(p, 1.0);
#if !CONSTANT_FACES && !FLAT_LIGHT
    vRelPosition = rel.xyz;
#endif
    // Normals by the cofactor matrix (det * inverse transpose): right under non-uniform scale,
    // three cross products instead of an inverse per vertex; the sign of det undoes mirroring.
    mat3 m = mat3(iModel);
    mat3 cof = mat3(cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1]));
#if CONSTANT_FACES || FLAT_LIGHT
    // The fragment shader's formula, with the normal (and for constant faces the texture
    // coordinate) the triangle's three vertices share; front faces only: back faces are culled.
    vec3 nf = normalize(sign(dot(m[0], cof[0])) * (cof * n));
    float sun = max(dot(nf, uLightDirection), 0.0);
    vec3 ambient = mix(uGroundColor, uSkyColor, 0.5 + 0.5 * nf.y);
    vec3 light = ambient + uLightColor * sun;
#if CONSTANT_FACES
    vec4 base = uBaseColor * iTint;
    if (uHasTexture) base *= textureLod(uTexture, aTexcoord, 0.0);
    vColor = vec4(linearToSrgb(base.rgb * light), base.a);
#else
    vBase = uBaseColor * iTint;
    vLight = light;
    vTexcoord = aTexcoord;
#endif
#else
    vNormal = sign(dot(m[0], cof[0])) * (cof * n);
    vTexcoord = aTexcoord;
    vTint = iTint;
    vRegion = vec4(equal(vec4(aRegion), vec4(1.0, 2.0, 3.0, 4.0)));
    vLook = iLook;
#endif
    gl_Position = uProjection * (uViewRotation * rel);
#endif
}
)GLSL";

constexpr const char* kSrgbEncode = R"GLSL(
vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
)GLSL";

constexpr const char* kConstantFragment = R"GLSL(#version 330 core
flat in vec4 vColor;
out vec4 fragColor;
void main() { fragColor = vColor; }
)GLSL";

constexpr const char* kFlatLightFragment = R"GLSL(#version 330 core
in vec2 vTexcoord;
flat in vec4 vBase;
flat in vec3 vLight;
uniform sampler2D uTexture;
uniform bool uHasTexture;
out vec4 fragColor;
SRGB_ENCODE
void main() {
    vec4 base = vBase;
    if (uHasTexture) base *= texture(uTexture, vTexcoord);
    fragColor = vec4(linearToSrgb(base.rgb * vLight), base.a);
}
)GLSL";

// Replaces the lines SRGB_ENCODE and BODY_LOOK by their functions, shared by the shading paths.
std::string withSrgbEncode(std::string text) {
    for (const auto& [mark, body] : {std::pair{std::string("SRGB_ENCODE"), std::string(kSrgbEncode)},
                                     std::pair{std::string("BODY_LOOK"), bodyLookGlsl()}}) {
        const std::size_t at = text.find(mark);
        if (at != std::string::npos) text.replace(at, mark.size(), body);
    }
    return text;
}

constexpr const char* kFragment = R"GLSL(#version 330 core
in vec3 vRelPosition;
in vec3 vNormal;
in vec2 vTexcoord;
flat in vec4 vTint;
in vec4 vRegion;
flat in uvec4 vLook;

uniform vec4 uBaseColor;
uniform sampler2D uTexture;
uniform bool uHasTexture;
uniform bool uHasNormals;
uniform vec3 uLightDirection;  // normalised, towards the light
uniform vec3 uLightColor;
uniform vec3 uSkyColor;
uniform vec3 uGroundColor;
uniform bool uFlatTint;        // ID renders: the tint as is
uniform bool uRegionIds;       // region maps: the body region / 255 in red, unlit

out vec4 fragColor;

SRGB_ENCODE
BODY_LOOK

void main() {
    if (uFlatTint) {
        fragColor = vTint;
        return;
    }
    if (uRegionIds) {
        float r = 0.0, best = 0.0;
        for (int i = 0; i < 4; ++i)
            if (vRegion[i] > best) best = vRegion[i], r = float(i + 1);
        fragColor = vec4(r / 255.0, 0.0, 0.0, 1.0);
        return;
    }
    vec4 base = uBaseColor * vTint;
    if (uHasTexture) base *= texture(uTexture, vTexcoord);
    base.rgb = recolour(base.rgb, vRegion, vLook);
    vec3 n;
    if (uHasNormals) {
        n = normalize(vNormal);
        if (!gl_FrontFacing) n = -n;  // two-sided lighting when back faces are drawn
    } else {
        n = normalize(cross(dFdx(vRelPosition), dFdy(vRelPosition)));  // flat: faces the eye
    }
    float sun = max(dot(n, uLightDirection), 0.0);
    vec3 ambient = mix(uGroundColor, uSkyColor, 0.5 + 0.5 * n.y);
    fragColor = vec4(linearToSrgb(base.rgb * (ambient + uLightColor * sun)), base.a);
}
)GLSL";

// The vertex body with its switches set.
std::string vertexVariant(int influences, bool feedback, bool constantFaces, bool flatLight, int keyPose, bool keyPoseFill,
                          bool morph = false) {
    const auto flag = [](bool b) { return b ? "1" : "0"; };
    return std::string("#version 330 core\n#define INFLUENCES ") + std::to_string(influences) + "\n#define FEEDBACK " +
           flag(feedback) + "\n#define CONSTANT_FACES " + flag(constantFaces) + "\n#define FLAT_LIGHT " + flag(flatLight) +
           "\n#define KEYPOSE " + std::to_string(keyPose) + "\n#define KEYPOSE_FILL " + flag(keyPoseFill) + "\n#define MORPH " +
           flag(morph) + "\n" + withSrgbEncode(kVertexBody);
}

}  // namespace

std::string bodyLookGlsl() {
    return R"GLSL(
vec3 srgbToLinear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c)); }
// A packed sRGB BodyLook colour, decoded to linear RGB; alpha 0 (keep the material) in .a.
vec4 lookColour(uint word) {
    vec4 c = vec4(float(word & 255u), float((word >> 8) & 255u), float((word >> 16) & 255u), float(word >> 24)) / 255.0;
    return vec4(srgbToLinear(c.rgb), c.a);
}
// Impostors: the actor's colour (linear) for the region a region map shows at `at` (uv, layer),
// white where it shows none or the look keeps the material.
vec3 regionPaint(sampler2DArray regions, vec3 at, uvec4 look) {
    int r = int(texture(regions, at).r * 255.0 + 0.5);
    if (r < 1 || r > 4) return vec3(1.0);
    vec4 c = lookColour(look[r - 1]);
    return c.a > 0.0 ? c.rgb : vec3(1.0);
}
// Impostors: the blend `c` of premultiplied sRGB cells, and `paint`, the same blend of each cell's
// coverage times its region colour: the straight colour the actor's look makes of it (sRGB).
vec3 wearLook(vec4 c, vec3 paint) { return linearToSrgb(srgbToLinear(c.rgb / c.a) * paint / c.a); }
// The albedo `a` (linear) recoloured by the one-hot (or blended) body region `region` with the
// actor's `look`: the colour times bodyRecolourGrey(luminance), where the look colours the region.
vec3 recolour(vec3 a, vec4 region, uvec4 look) {
    float grey = clamp(0.3 + 1.4 * dot(a, vec3(0.2126, 0.7152, 0.0722)), 0.0, 1.0);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < 4; ++i) {
        if (region[i] <= 0.0) continue;
        vec4 c = lookColour(look[i]);
        if (c.a <= 0.0) continue;
        sum += region[i] * c.rgb;
        weight += region[i];
    }
    return weight > 0.0 ? mix(a, sum / weight * grey, min(weight, 1.0)) : a;
}
)GLSL";
}

std::string srgbEncodeGlsl() { return kSrgbEncode; }

std::string vertexShaderSource(int influences, bool feedback, bool morph) {
    return vertexVariant(influences, feedback, false, false, 0, false, morph);
}

std::string keyPoseFillVertexShaderSource(int influences) { return vertexVariant(influences, true, false, false, 0, true); }

std::string keyPoseVertexShaderSource(bool interpolative) {
    return vertexVariant(0, false, false, false, interpolative ? 2 : 1, false);
}

std::string constantFaceVertexShaderSource() { return vertexVariant(0, false, true, false, 0, false); }

std::string flatLightVertexShaderSource() { return vertexVariant(0, false, false, true, 0, false); }

std::string flatLightFragmentShaderSource() { return withSrgbEncode(kFlatLightFragment); }

std::string fragmentShaderSource() { return withSrgbEncode(kFragment); }

std::string constantFaceFragmentShaderSource() { return kConstantFragment; }

}  // namespace throng::detail

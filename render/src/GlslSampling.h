#pragma once
// Private: the GLSL of the premultiplied bilinear sample every GPU warp shares with the CPU's
// samplePremultiplied (BeierNeely.cpp), so that the CPU and GPU paths agree to rounding. The shader
// that includes it defines `vec4 texel(int image, ivec2 p)` first (transparent outside the image).

namespace throng::detail {

/// `vec4 samplePremultiplied(int image, vec2 position)`: pixel centres at +0.5, by hand with texel().
inline constexpr const char* kGlslSamplePremultiplied = R"(
vec4 samplePremultiplied(int image, vec2 position) {
    vec2 f = position - 0.5;
    vec2 f0 = floor(f);
    vec2 w = f - f0;
    if (!(abs(f0.x) < 1e6 && abs(f0.y) < 1e6)) return vec4(0.0);
    ivec2 i = ivec2(f0);
    vec4 top = texel(image, i) * (1.0 - w.x) + texel(image, i + ivec2(1, 0)) * w.x;
    vec4 bottom = texel(image, i + ivec2(0, 1)) * (1.0 - w.x) + texel(image, i + ivec2(1, 1)) * w.x;
    return top * (1.0 - w.y) + bottom * w.y;
}
)";

}  // namespace throng::detail

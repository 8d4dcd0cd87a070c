#version 450
// What the texture unit's trilinear filter returns between two texels (vulkan_sampler_probe.cpp): a
// 2x1x1 image holding 0 and full scale, read at COUNT evenly spaced points from the first texel's
// centre to the second's. The exact answer at point i is i / (COUNT - 1).
layout(local_size_x = 64) in;
const uint COUNT = 4097;  // vulkan_sampler_probe.cpp: kPoints

layout(binding = 0) uniform sampler3D probeTexture;
layout(std430, binding = 1) writeonly buffer Read { float values[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= COUNT) return;
    // Texel centres lie at x = 0.25 and 0.75; with COUNT - 1 a power of two every x is exact in float.
    float x = 0.25 + 0.5 * (float(i) / float(COUNT - 1));
    values[i] = textureLod(probeTexture, vec3(x, 0.5, 0.5), 0.0).r;
}

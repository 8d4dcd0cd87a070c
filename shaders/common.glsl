// Shared by the compute shaders of the Vulkan backend (vulkan_renderer.cpp): the bindings, the rays, the
// volume sampler, the transfer function and the frame's counters, each a port of the CPU code in float
// (the rays in double, as the CPU makes them).
//
// The volume is read from a storage buffer in its native type and interpolated here with the
// formula and clamping of grid_sampler.h, not with a hardware sampler: texture units filter with
// low-precision weights (8 fractional bits on many GPUs), far from float. The sampler is there for
// comparison (SAMPLER = 1, vri-render --interpolation sampler): the same voxels in a 3D image.
//
// `precise` keeps the compiler from fusing multiplies and adds: the CPU code is built with
// -ffp-contract=off, and fused operations would round differently.

layout(local_size_x = 8, local_size_y = 8) in;

// Specialisation constants: one pipeline per combination, so that each shader is straight-line code.
layout(constant_id = 0) const int VOXEL_TYPE = 0;  // 0 uint8, 1 uint16, 2 float32, 3 the analytic linear field
layout(constant_id = 1) const int EMISSION = 0;    // 0 colour times extinction, 1 colour
layout(constant_id = 4) const int SAMPLER = 0;     // 0 interpolate here, 1 the texture unit's trilinear filter
const int ANALYTIC = 3;

layout(std140, binding = 0) uniform Params {
    vec4 scale;     // texture coordinate -> voxel index: x = u * scale - offset
    vec4 offset;
    vec4 maxCoord;  // dims - 1
    ivec4 maxBase;  // max(dims - 2, 0)
    ivec4 stride;   // voxels; 0 along an axis of a single layer. w: the pre-integration table's size (march.comp)
    vec4 dims;      // the grid resolution paper A's placements use. w: the table's segment length (march.comp)
    vec4 eyeU;      // the eye in texture coordinates
    float lo, invRange;  // normalisation: s = (value - lo) * invRange
    float samplingRate, earlyTermination;
    float h0, hMin, hMax, epsPerVoxel;  // paper B, voxels; hMax may be +inf
    int width, height, tfCount, accepted;  // accepted: 0 Richardson, 1 paper (D + |D - S| / 15)
    ivec4 bricks;   // empty-space bricks per axis (occupancy_grid.h); w: 1 when skipping empty space
    vec4 maxIndex;  // dims - 1, the voxel index range the bricks cover
    vec4 texel;     // the sampler: 1 / dims, and in w the voxel value of a texel that reads 1 (255 for R8 unorm)
    ivec4 region;   // the pixels rendered: x, y, width, height in pixels of the whole width x height image
    // The camera (Camera's basis, in double) and the box in world units, for the rays.
    dvec4 eye;      // w: zoom
    dvec4 forward;  // w: tan of half the horizontal field of view
    dvec4 right;    // w: tan of half the vertical field of view
    dvec4 up;       // w: the zoom centre's x, in pixels of the full frame
    dvec4 boxLo;    // w: the zoom centre's y
    dvec4 boxHi;    // w: the jitter's seed (march.comp; jitter.h), or -1 for no jitter
} P;

layout(std430, binding = 1) readonly buffer Volume { uint words[]; };
// Per transfer function point i: s, r, g, b, tau, then the differences to point i + 1 as the CPU
// computes them (in double, then rounded to float).
layout(std430, binding = 2) readonly buffer TransferFunction { float tf[]; };
// The frame's counters, summed here: per counter a 64-bit count as (low word, high word), zero before
// the dispatch. Which counter is which, the shader says (TOTAL_*).
layout(std430, binding = 3) coherent buffer Totals { uint totals[]; };
layout(std430, binding = 4) writeonly buffer Output { vec4 pixels[]; };
// OccupancyGrid::emptyFlags(), one byte per brick, x fastest: 1 where the transfer function gives
// nothing to any sample that the brick (and a one-voxel margin) can produce.
layout(std430, binding = 5) readonly buffer Occupancy { uint emptyWords[]; };
// The voxels again, as a 3D image filtered linearly and clamped to the edge (used when SAMPLER = 1).
layout(binding = 6) uniform sampler3D volumeTexture;

// Adds v to counter i, carrying into its high word when the low word wraps: the adder whose
// atomicAdd wraps it, and only that one, sees the sum come out below the old value.
void addTotal(int i, uint v) {
    if (v == 0u) return;
    uint old = atomicAdd(totals[2 * i], v);
    if (old + v < old) atomicAdd(totals[2 * i + 1], 1u);
}
const int TOTAL_RAYS_HIT = 8;  // after the shaders' eight counters

// The ray of a pixel, made as the CPU makes it, in double: Camera::direction (glm::normalize is
// v * (1 / sqrt(dot(v, v))), the dot product summed x, y, z), clipRay against the box, and the entry and
// exit points in texture coordinates rounded to float (Box::toTexture). With every operation correctly
// rounded, as IEEE double addition, multiplication, division and square root are on the device (Vulkan
// requires shaderFloat64; lavapipe computes them on the CPU's units), these are the CPU's segments bit
// for bit. False when the ray misses the box.
bool makeRay(ivec2 pixel, out vec3 entry, out vec3 exit, out double worldLength) {
    precise double zoom = P.eye.w;
    precise double fx = P.up.w + (double(pixel.x) + 0.5 - 0.5 * double(P.width)) / zoom;
    precise double fy = P.boxLo.w + (double(pixel.y) + 0.5 - 0.5 * double(P.height)) / zoom;
    precise double x = (2.0 * fx / double(P.width) - 1.0) * P.forward.w;
    precise double y = (1.0 - 2.0 * fy / double(P.height)) * P.right.w;
    precise dvec3 v = P.forward.xyz + x * P.right.xyz + y * P.up.xyz;
    precise double norm = v.x * v.x + v.y * v.y + v.z * v.z;
    precise double inverse = 1.0 / sqrt(norm);
    precise dvec3 dir = v * inverse;
    dvec3 eye = P.eye.xyz;
    double tNear = 0.0, tFar = 1.0 / 0.0;
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (eye[a] < P.boxLo[a] || eye[a] > P.boxHi[a]) return false;
            continue;
        }
        precise double t0 = (P.boxLo[a] - eye[a]) / dir[a];
        precise double t1 = (P.boxHi[a] - eye[a]) / dir[a];
        if (t0 > t1) {
            double swap = t0;
            t0 = t1;
            t1 = swap;
        }
        tNear = max(tNear, t0);
        tFar = min(tFar, t1);
        if (tNear > tFar) return false;
    }
    precise dvec3 extent = P.boxHi.xyz - P.boxLo.xyz;
    precise dvec3 near = eye + tNear * dir, far = eye + tFar * dir;
    entry = vec3((near - P.boxLo.xyz) / extent);
    exit = vec3((far - P.boxLo.xyz) / extent);
    worldLength = tFar - tNear;
    return true;
}

// The world length per unit of the ray's parameter (texture units, or voxels in `length`), as render()
// derives it: the float length of the ray's parameter range, the world length divided by it in double.
float worldPerUnit(double worldLength, float length) {
    return length > 0.0 ? float(worldLength / double(length)) : 0.0;
}

const int BRICK_SHIFT = 3;  // OccupancyGrid::kBrickShift

// OccupancyGrid::visit in float for the index-space ray x0 + t dxdt: whether the brick at t is empty,
// and the parameter where the ray leaves it. The one-voxel margin of the emptiness test covers the
// rounding of float positions, so a skipped sample is one that would have added exactly nothing.
bool brickEmpty(vec3 x0, vec3 dxdt, float t, out float tExit) {
    uint cell = 0u;
    tExit = 1.0 / 0.0;
    for (int a = 2; a >= 0; --a) {
        precise float x = clamp(x0[a] + t * dxdt[a], 0.0, P.maxIndex[a]);
        int m = min(int(x) >> BRICK_SHIFT, P.bricks[a] - 1);
        cell = cell * uint(P.bricks[a]) + uint(m);
        if (dxdt[a] > 0.0 && m + 1 < P.bricks[a])
            tExit = min(tExit, (float((m + 1) << BRICK_SHIFT) - x0[a]) / dxdt[a]);
        else if (dxdt[a] < 0.0 && m > 0)
            tExit = min(tExit, (float(m << BRICK_SHIFT) - x0[a]) / dxdt[a]);
    }
    return ((emptyWords[cell >> 2] >> ((cell & 3u) * 8u)) & 0xffu) != 0u;
}

float voxel(uint i) {
    if (VOXEL_TYPE == 0) return float((words[i >> 2] >> ((i & 3u) * 8u)) & 0xffu);
    if (VOXEL_TYPE == 1) return float((words[i >> 1] >> ((i & 1u) * 16u)) & 0xffffu);
    return uintBitsToFloat(words[i]);
}

precise float lerp1(float a, float b, float t) { return a + t * (b - a); }

// GridSampler::operator() (or LinearFieldSampler): the normalised scalar at texture coordinate u.
float sampleScalar(vec3 u) {
    if (VOXEL_TYPE == ANALYTIC) return u.x;
    precise vec3 x = u * P.scale.xyz - P.offset.xyz;
    if (SAMPLER == 1) {
        // Voxel index x lies at texel centre (x + 0.5) / dims; clamping to the edge clamps x to
        // [0, dims - 1] as the CPU does.
        precise vec3 t = (x + 0.5) * P.texel.xyz;
        precise float s = (textureLod(volumeTexture, t, 0.0).r * P.texel.w - P.lo) * P.invRange;
        return s;
    }
    uint base = 0u;
    precise vec3 w;
    for (int a = 0; a < 3; ++a) {
        precise float c = clamp(x[a], 0.0, P.maxCoord[a]);
        int i = min(int(c), P.maxBase[a]);
        w[a] = c - float(i);
        base += uint(i) * uint(P.stride[a]);
    }
    uint sx = uint(P.stride.x), sy = uint(P.stride.y), sz = uint(P.stride.z);
    precise float c00 = lerp1(voxel(base), voxel(base + sx), w.x);
    precise float c10 = lerp1(voxel(base + sy), voxel(base + sy + sx), w.x);
    precise float c01 = lerp1(voxel(base + sz), voxel(base + sz + sx), w.x);
    precise float c11 = lerp1(voxel(base + sz + sy), voxel(base + sz + sy + sx), w.x);
    precise float c0 = lerp1(c00, c10, w.y);
    precise float c1 = lerp1(c01, c11, w.y);
    precise float s = (lerp1(c0, c1, w.z) - P.lo) * P.invRange;
    return s;
}

// TransferFunction::operator(): (r, g, b, tau), piecewise linear, constant beyond the ends; at a jump
// (equal s) the value is taken from the right.
vec4 transfer(float s) {
    int last = P.tfCount - 1;
    if (!(s >= tf[0])) return vec4(tf[1], tf[2], tf[3], tf[4]);
    if (!(s < tf[10 * last])) return vec4(tf[10 * last + 1], tf[10 * last + 2], tf[10 * last + 3], tf[10 * last + 4]);
    int i = 0;
    while (s >= tf[10 * (i + 1)]) ++i;
    int o = 10 * i;
    precise float w = (s - tf[o]) / tf[o + 5];
    precise vec4 v = vec4(tf[o + 1], tf[o + 2], tf[o + 3], tf[o + 4]) + w * vec4(tf[o + 6], tf[o + 7], tf[o + 8], tf[o + 9]);
    return v;
}

#version 450
// Paper A's fixed-step methods, one invocation per pixel: Riemann (or opacity-corrected composite)
// over the samples of one of the four placements (or jittered, when P.boxHi.w holds a seed), or
// pre-integrated classification over the segments the samples stand for, as render.cpp's marchSamples, placement.h's
// placeSamples and integrator.h's RayAccumulator compute them in float, skipping empty bricks as
// marchSamples does (which changes no bit of the image).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(constant_id = 2) const int PLACEMENT = 1;   // 0 eye, 1 entry, 2 entry-exit, 3 entry-exit-corner
layout(constant_id = 3) const int COMPOSITE = 0;   // 0 Riemann, 1 opacity-corrected compositing
layout(constant_id = 5) const int PREINTEGRATED = 0;  // 0 samples; 1 or 2: pre-integration of that order

// preintegration_table.h's table in float: N x N entries (front i, back j at (i N + j) 4) of R, G, B and
// depth, then for order 2 as many derivatives in the midpoint's deviation. N is P.stride.w, the segment
// length it was integrated for P.dims.w (world units); order 2 ends with the 4 upper bounds of R, G, B, depth.
layout(std430, binding = 7) readonly buffer Preintegration { float preint[]; };

// exp(x) - 1 without the cancellation of the plain difference near 0 (Kahan's trick), for
// composite's alpha = -expm1(-tau dx).
precise float expm1(float x) {
    precise float u = exp(x);
    if (u == 1.0) return x;
    precise float um1 = u - 1.0;
    if (um1 == -1.0) return -1.0;
    return um1 * x / log(u);
}

// placement.h's countBelowEnd: as many samples as have t < tEnd, counted on the positions evaluated.
int countBelowEnd(precise float tStart, precise float tIncr, precise float tEnd) {
    int n = tStart < tEnd ? int(ceil((tEnd - tStart) / tIncr)) : 0;
    while (n > 0 && !(tStart + float(n - 1) * tIncr < tEnd)) --n;
    while (tStart + float(n) * tIncr < tEnd) ++n;
    return n;
}

// jitter.h's mixBits ("lowbias32") and jitterFraction, in the same 32-bit integer arithmetic: a multiple
// of 2^-24 in [0, 1), exact in float, so the CPU and the device start every ray at the same t.
uint mixBits(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
float jitterFraction(ivec2 pixel, uint seed) {
    uint h = mixBits(uint(pixel.x) ^ mixBits(uint(pixel.y) ^ mixBits(seed)));
    return float(h >> 8) * (1.0 / 16777216.0);
}

// PreintegrationTable::operator() in float: the table's entries around (front, back) interpolated
// bilinearly, plus delta times the derivatives' for order 2.
precise float tableCoordinate(float s, out int i) {
    int n = P.stride.w;
    precise float x = (s > 0.0 ? (s < 1.0 ? s : 1.0) : 0.0) * float(n - 1);
    i = min(int(x), n - 2);
    return x - float(i);
}
vec4 lookUpSegment(float front, float back, float delta) {
    int i, j;
    precise float fi = tableCoordinate(front, i), fj = tableCoordinate(back, j);
    int n = P.stride.w;
    int at = (i * n + j) * 4, row = n * 4;
    precise vec4 out4;
    for (int c = 0; c < 4; ++c) {
        precise float near = lerp1(preint[at + c], preint[at + 4 + c], fj);
        precise float far = lerp1(preint[at + row + c], preint[at + row + 4 + c], fj);
        out4[c] = lerp1(near, far, fi);
    }
    if (PREINTEGRATED == 2) {
        // Each value within [0, the segment's physical upper bound] (PreintegrationTable::upperBound), the
        // bounds stored after the slopes.
        int slopes = n * n * 4, upper = 2 * n * n * 4;
        for (int c = 0; c < 4; ++c) {
            precise float near = lerp1(preint[slopes + at + c], preint[slopes + at + 4 + c], fj);
            precise float far = lerp1(preint[slopes + at + row + c], preint[slopes + at + row + 4 + c], fj);
            precise float value = out4[c] + delta * lerp1(near, far, fi);
            out4[c] = value > 0.0 ? (value < preint[upper + c] ? value : preint[upper + c]) : 0.0;
        }
    }
    return out4;
}

// The ray of one pixel; its samples placed and evaluated go to the counters.
void trace(ivec2 pixel, int id) {
    pixels[id] = vec4(0.0);
    vec3 entry, exit;
    double worldLength;
    if (!makeRay(pixel, entry, exit, worldLength)) return;  // the ray misses the box
    if (worldLength > 0.0) addTotal(TOTAL_RAYS_HIT, 1u);

    // placeSamples
    precise vec3 ray = exit - entry;
    precise float tEnd = length(ray);
    if (!(tEnd > 0.0)) return;
    precise float samples;
    if (PLACEMENT == 0 || PLACEMENT == 1) samples = length(ray * P.dims.xyz) * P.samplingRate;
    else if (PLACEMENT == 2) samples = floor(length(ray * P.dims.xyz) * P.samplingRate);
    else samples = ceil(P.samplingRate * length(ray * (P.dims.xyz - vec3(1.0))));
    if (!(samples > 0.0) || isinf(samples)) return;
    precise float tIncr = tEnd / samples;
    precise float tStart;
    if (PLACEMENT == 0) {
        precise float numSteps = length(entry - P.eyeU.xyz) / tIncr;
        tStart = (1.0 - (numSteps - floor(numSteps))) * tIncr;
    } else {
        tStart = 0.5 * tIncr;
    }
    int count = PLACEMENT >= 2 ? int(samples) : countBelowEnd(tStart, tIncr, tEnd);
    // jitterSchedule: the first sample at the pixel's fraction of the step past the entry.
    if (P.boxHi.w >= 0.0) {
        tStart = jitterFraction(pixel, uint(P.boxHi.w)) * tIncr;
        count = countBelowEnd(tStart, tIncr, tEnd);
    }

    // marchSamples
    precise vec3 du = ray / tEnd;
    precise float dx = tIncr * worldPerUnit(worldLength, tEnd);
    precise float r = 0.0, g = 0.0, bl = 0.0, transparency = 1.0;
    if (PREINTEGRATED != 0) {
        // marchSegments: sample k stands for the segment from half a step before it to half a step after,
        // looked up from the scalars at its ends (and at the sample, for order 2); every segment is looked up.
        if (count == 0) return;
        precise float lengthRatio = dx / P.dims.w;
        precise float halfStep = 0.5 * tIncr;
        precise float front = sampleScalar(entry + (tStart - halfStep + 0.0 * tIncr) * du);
        for (int k = 0; k < count; ++k) {
            precise float back = sampleScalar(entry + (tStart - halfStep + float(k + 1) * tIncr) * du);
            precise float delta = PREINTEGRATED == 2 ? sampleScalar(entry + (tStart + float(k) * tIncr) * du) - 0.5 * (front + back) : 0.0;
            precise vec4 v = lookUpSegment(front, back, delta);
            front = back;
            // RayAccumulator::addSegment
            if (v.w == 0.0 && v.x == 0.0 && v.y == 0.0 && v.z == 0.0) continue;
            precise float depth = v.w * lengthRatio;
            precise float scale = lengthRatio;  // no extinction: the colour grows with the length
            if (lengthRatio == 1.0) scale = 1.0;
            else if (v.w > 0.0) scale = expm1(-depth) / expm1(-v.w);
            precise float w = transparency * scale;
            r += w * v.x;
            g += w * v.y;
            bl += w * v.z;
            transparency *= exp(-depth);
        }
        pixels[id] = vec4(r, g, bl, 1.0 - transparency);
        addTotal(0, uint(count));
        addTotal(1, uint(count));
        return;
    }
    precise vec3 x0 = entry * P.scale.xyz - P.offset.xyz;  // the ray in voxel index space, as the bricks
    precise vec3 dxdt = du * P.scale.xyz;
    float knownOccupiedUntil = -1.0 / 0.0;
    int k = 0, evaluated = 0;
    while (k < count) {
        precise float t = tStart + float(k) * tIncr;
        if (P.bricks.w != 0 && t >= knownOccupiedUntil) {
            float tExit;
            if (brickEmpty(x0, dxdt, t, tExit)) {
                // To the first sample at or past the exit, as marchSamples: every one skipped lies before it.
                if (!(tExit < tEnd)) {
                    k = count;
                    break;
                }
                int next = clamp(int(ceil((tExit - tStart) / tIncr)), k + 1, count);
                while (next > k + 1 && tStart + float(next - 1) * tIncr >= tExit) --next;
                k = next;
                continue;
            }
            knownOccupiedUntil = tExit;
        }
        vec4 v = transfer(sampleScalar(entry + t * du));
        ++k;
        ++evaluated;
        // RayAccumulator::add
        if (!(v.w == 0.0 && EMISSION == 0)) {
            precise float attenuation = exp(-v.w * dx);
            precise float weight;
            if (COMPOSITE == 0) {
                weight = EMISSION == 0 ? v.w * dx : dx;
            } else {
                precise float alpha = -expm1(-v.w * dx);
                weight = EMISSION == 0 ? alpha : v.w > 0.0 ? alpha / v.w : dx;
            }
            precise float w = transparency * weight;
            r += w * v.x;
            g += w * v.y;
            bl += w * v.z;
            transparency *= attenuation;
        }
        if (transparency < P.earlyTermination) break;
    }
    pixels[id] = vec4(r, g, bl, 1.0 - transparency);
    addTotal(0, uint(k));  // samples placed
    addTotal(1, uint(evaluated));
}

void main() {
    ivec2 local = ivec2(gl_GlobalInvocationID.xy);  // in the region; the output holds the region's pixels
    if (local.x < P.region.z && local.y < P.region.w) trace(P.region.xy + local, local.y * P.region.z + local.x);
}

#version 450
// Paper B's Simpson methods, one invocation per pixel: adaptive_simpson.h's AdaptiveSimpsonRay and
// SimpsonWindow ported to float, coupled or decoupled (uniform Simpson is coupled with
// h0 = h_min = h_max), as render.cpp's integrateSimpson calls them, with its empty-space shortcut.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(constant_id = 2) const int COUPLED = 1;

// The ray: v in voxels of ray, point = entry + v * du; in voxel index space x0 + v * dxdt.
vec3 entry, du, x0, dxdt;
float worldPerVoxel;

// AdaptiveCounts of this ray.
uint innerTries = 0u, innerFailures = 0u, outerTries = 0u, outerFailures = 0u;
uint outerSteps = 0u, acceptedAtMinimum = 0u, pointsUsed = 0u, pointsEvaluated = 0u;

// AdaptiveResult
precise float outR = 0.0, outG = 0.0, outB = 0.0, outAlpha = 0.0, outTransparency = 1.0;

// SimpsonWindow: the five points of the last try and their (kappa, r, g, b), reused when a later try
// lands on the same positions.
float wx[5];
vec4 wp[5];
bool wValid = false;

// Extinction and emission per voxel of ray at v (render.cpp's evaluate).
vec4 evaluate(float v) {
    precise vec3 u = entry + v * du;
    vec4 x = transfer(sampleScalar(u));
    precise float kappa = x.w * worldPerVoxel;
    precise float weight = EMISSION == 0 ? kappa : worldPerVoxel;
    precise vec4 p = vec4(kappa, x.x * weight, x.y * weight, x.z * weight);
    return p;
}

// render.cpp's emptyAlong: true when [a, b] lies in empty bricks only; gives up (false) rather than
// loop on a brick exit that rounding leaves on the wrong side.
bool emptyAlong(float a, float b) {
    if (P.bricks.w == 0) return false;
    float t = a;
    for (int visits = 0; visits < 64; ++visits) {
        float tExit;
        if (!brickEmpty(x0, dxdt, t, tExit)) return false;
        if (tExit >= b) return true;
        if (!(tExit > t)) return false;
        t = tExit;
    }
    return false;
}

void place(float a, float b) {
    precise float h = b - a;
    precise float x[5] = float[5](a, a + h * 0.25, a + h * 0.5, a + h * 0.75, b);
    int reused[5];  // the previous window's point at the same position, or -1
    bool fresh = false;
    for (int k = 0; k < 5; ++k) {
        reused[k] = -1;
        if (wValid)
            for (int i = 0; i < 5; ++i)
                if (wx[i] == x[k]) {
                    reused[k] = i;
                    break;
                }
        fresh = fresh || reused[k] < 0;
    }
    // Asked once, and only when a point must be evaluated (then every such point is exactly zero): asking
    // inside the loop below would, on SIMD devices, walk the bricks once per point for the whole group.
    bool empty = fresh && emptyAlong(a, b);
    vec4 next[5];
    for (int k = 0; k < 5; ++k) {
        if (reused[k] >= 0) {
            next[k] = wp[reused[k]];
        } else if (!empty) {
            next[k] = evaluate(x[k]);
            ++pointsEvaluated;
        } else {
            next[k] = vec4(0.0);
        }
    }
    pointsUsed += 5u;
    wx = x;
    wp = next;
    wValid = true;
}

bool allZero() {
    for (int k = 0; k < 5; ++k)
        if (wp[k] != vec4(0.0)) return false;
    return true;
}

precise float halfStep(float f0, float f1, float f2, float h) { return h / 12.0 * (f0 + 4.0 * f1 + f2); }
precise float quarter(float f0, float f1, float f2, float h) { return h / 48.0 * (5.0 * f0 + 8.0 * f1 - f2); }
precise float whole(float f0, float f2, float f4, float h) { return h / 6.0 * (f0 + 4.0 * f2 + f4); }
precise float tolerance(float h) { return P.epsPerVoxel * h; }
precise float acceptedValue(float d, float s) { return P.accepted == 0 ? d + (d - s) / 15.0 : d + abs(d - s) / 15.0; }

// Algorithm 2's step control: the proposal and whether the last try succeeded.
struct Control {
    float proposal;
    bool lastSucceeded;
};
void succeeded(inout Control c) {
    if (c.lastSucceeded) c.proposal = min(c.proposal * 2.0, P.hMax);
    c.lastSucceeded = true;
}
void failed(inout Control c, float tried) {
    c.proposal = max(tried / 2.0, P.hMin);
    c.lastSucceeded = false;
}

// Algorithm 2 on the four channels over [t, end], the transparency carried along.
void integrateOuter(float t, float end, inout Control control) {
    while (t < end) {
        precise float h = min(control.proposal, end - t);
        float b = h == end - t ? end : t + h;
        place(t, b);
        float k0 = wp[0].x, k1 = wp[1].x, k2 = wp[2].x, k3 = wp[3].x, k4 = wp[4].x;
        precise float depthHalf = halfStep(k0, k1, k2, h);
        precise float depthD = depthHalf + halfStep(k2, k3, k4, h);
        precise float depthS = whole(k0, k2, k4, h);
        precise float depth[5] = float[5](0.0, quarter(k0, k1, k2, h), depthHalf, depthHalf + quarter(k2, k3, k4, h), depthD);
        precise vec4 f[5];  // per point: emission (r, g, b) and extinction (alpha) times transparency
        for (int k = 0; k < 5; ++k) {
            precise float tr = outTransparency * exp(-depth[k]);
            f[k] = vec4(wp[k].y * tr, wp[k].z * tr, wp[k].w * tr, wp[k].x * tr);
        }
        precise float d[4], s[4];
        precise float e = 0.0;
        for (int c = 0; c < 4; ++c) {
            d[c] = halfStep(f[0][c], f[1][c], f[2][c], h) + halfStep(f[2][c], f[3][c], f[4][c], h);
            s[c] = whole(f[0][c], f[2][c], f[4][c], h);
            e = max(e, abs(d[c] - s[c]) / 15.0);
        }
        bool ok = e <= tolerance(h) || h <= P.hMin;
        ++outerTries;
        if (ok) {
            if (e > tolerance(h)) ++acceptedAtMinimum;
            ++outerSteps;
            outR += acceptedValue(d[0], s[0]);
            outG += acceptedValue(d[1], s[1]);
            outB += acceptedValue(d[2], s[2]);
            outAlpha += acceptedValue(d[3], s[3]);
            outTransparency *= exp(-acceptedValue(depthD, depthS));
            succeeded(control);
            t = b;
        } else {
            ++outerFailures;
            failed(control, h);
        }
    }
}

// The ray of one pixel, as integrateSimpson, in voxels of ray; its counts go to the counters.
void trace(ivec2 pixel, int id) {
    pixels[id] = vec4(0.0);
    vec3 exit;
    double worldLength;
    if (!makeRay(pixel, entry, exit, worldLength)) return;  // the ray misses the box
    if (worldLength > 0.0) addTotal(TOTAL_RAYS_HIT, 1u);
    precise vec3 along = exit - entry;
    precise float rayLength = length(along * P.dims.xyz);
    if (!(rayLength > 0.0)) return;
    du = along / rayLength;
    x0 = entry * P.scale.xyz - P.offset.xyz;
    dxdt = du * P.scale.xyz;
    worldPerVoxel = worldPerUnit(worldLength, rayLength);

    // AdaptiveSimpsonRay::integrate
    float h0 = min(P.h0, P.hMax);
    Control inner = Control(h0, true), outer = Control(h0, true);
    float t = 0.0;
    while (t < rayLength && !(outTransparency < P.earlyTermination)) {
        float end;
        for (;;) {
            precise float h = min(inner.proposal, rayLength - t);
            end = h == rayLength - t ? rayLength : t + h;
            place(t, end);
            precise float d = halfStep(wp[0].x, wp[1].x, wp[2].x, h) + halfStep(wp[2].x, wp[3].x, wp[4].x, h);
            precise float s = whole(wp[0].x, wp[2].x, wp[4].x, h);
            precise float e = abs(d - s) / 15.0;
            bool ok = e <= tolerance(h) || h <= P.hMin;
            ++innerTries;
            if (ok && e > tolerance(h)) ++acceptedAtMinimum;
            if (ok) {
                succeeded(inner);
                if (allZero()) break;
                if (COUPLED == 1) outer = Control(h, true);
                integrateOuter(t, end, outer);
                break;
            }
            ++innerFailures;
            failed(inner, h);
        }
        t = end;
    }
    pixels[id] = vec4(outR, outG, outB, outAlpha);
    uint counts[8] = uint[8](pointsUsed, pointsEvaluated, innerTries, innerFailures, outerTries, outerFailures,
                             outerSteps, acceptedAtMinimum);
    for (int i = 0; i < 8; ++i) addTotal(i, counts[i]);
}

void main() {
    ivec2 local = ivec2(gl_GlobalInvocationID.xy);  // in the region; the output holds the region's pixels
    if (local.x < P.region.z && local.y < P.region.w) trace(P.region.xy + local, local.y * P.region.z + local.x);
}

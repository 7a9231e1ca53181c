// A post-process anti-aliasing pass (a simplified FXAA: Lottes, "FXAA",
// NVIDIA 2009, without the search along the edge's length). Per pixel: the
// luma range of its four neighbours; where it is below the contrast
// threshold the pixel is kept. Otherwise the edge is horizontal or
// vertical by the larger of the second differences, and the pixel is
// blended towards its neighbour across the edge by FXAA's sub-pixel amount
// (how far the pixel's luma lies from the 3x3 low-pass, smoothed and
// squared, FXAA's 0.75), at least a quarter and at most a half: a staircase
// becomes a ramp. Reads texels with
// textureLoad (no sampler); alpha is blended like colour, so a transparent
// background keeps its alpha 0 away from the object.
@group(0) @binding(0) var scene: texture_2d<f32>;

@vertex
fn vs_blit(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    return vec4<f32>(x * 2.0 - 1.0, 1.0 - y * 2.0, 0.0, 1.0);
}

fn at(p: vec2<i32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(scene));
    return textureLoad(scene, clamp(p, vec2<i32>(0), size - vec2<i32>(1)), 0);
}

// perceptual luma of a linear colour (sqrt approximates the sRGB curve)
fn luma(c: vec4<f32>) -> f32 {
    return sqrt(dot(c.rgb, vec3<f32>(0.299, 0.587, 0.114)));
}

@fragment
fn fs_fxaa(@builtin(position) q: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(q.xy);
    let c = at(p);
    let n = at(p + vec2<i32>(0, -1));
    let s = at(p + vec2<i32>(0, 1));
    let e = at(p + vec2<i32>(1, 0));
    let w = at(p + vec2<i32>(-1, 0));
    let lc = luma(c);
    let ln = luma(n);
    let ls = luma(s);
    let le = luma(e);
    let lw = luma(w);
    let hi = max(lc, max(max(ln, ls), max(le, lw)));
    let lo = min(lc, min(min(ln, ls), min(le, lw)));
    let range = hi - lo;
    // FXAA's quality thresholds: 1/16 absolute, 1/8 of the local maximum
    if range < max(0.0625, 0.125 * hi) {
        return c;
    }
    let lnw = luma(at(p + vec2<i32>(-1, -1)));
    let lne = luma(at(p + vec2<i32>(1, -1)));
    let lsw = luma(at(p + vec2<i32>(-1, 1)));
    let lse = luma(at(p + vec2<i32>(1, 1)));
    let horizontal = 2.0 * abs(ln + ls - 2.0 * lc) + abs(lne + lse - 2.0 * le) + abs(lnw + lsw - 2.0 * lw);
    let vertical = 2.0 * abs(le + lw - 2.0 * lc) + abs(lne + lnw - 2.0 * ln) + abs(lse + lsw - 2.0 * ls);
    var other: vec4<f32>;
    if horizontal >= vertical {
        other = select(s, n, abs(ln - lc) >= abs(ls - lc));
    } else {
        other = select(w, e, abs(le - lc) >= abs(lw - lc));
    }
    let average = (2.0 * (ln + ls + le + lw) + (lnw + lne + lsw + lse)) / 12.0;
    let sub = smoothstep(0.0, 1.0, clamp(abs(average - lc) / range, 0.0, 1.0));
    // at least a quarter across every edge found (standing in for FXAA's
    // blend along the edge's length), at most a half
    return mix(c, other, clamp(0.75 * sub * sub, 0.25, 0.5));
}

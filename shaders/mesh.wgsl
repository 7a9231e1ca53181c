// subdiv: mesh and line shaders shared by the window and offscreen rendering.
//
// Lighting (fs_mesh): Blinn-Phong with three directional lights,
//   colour = ka * base + sum_i I_i * (kd * max(n.l_i, 0) * base + ks * max(n.h_i, 0)^shininess)
// where light 0 is a headlight at the eye (l_0 = v, the direction to the eye), light 1 a key light
// fixed in the world (upper left front) and light 2 a weak fill from below;
// ka = 0.12, kd = 0.75, ks = 0.35 (white), shininess 48, intensities I_i in
// params.w, key_light.w, fill_light.w (render/scene.rs: HEADLIGHT_INTENSITY, ...).
// Two-sided: a back face (seen on open meshes) flips its normal and takes a
// warmer base colour. Flat shading takes the face normal from the screen-space
// derivatives of the world position, so no per-face vertex copies are needed.

struct View {
    proj: mat4x4<f32>,
    view: mat4x4<f32>,
    eye: vec4<f32>,        // camera position (world)
    forward: vec4<f32>,    // camera forward direction (world)
    key_light: vec4<f32>,  // direction towards the key light (world), w = intensity
    fill_light: vec4<f32>, // direction towards the fill light (world), w = intensity
    front_color: vec4<f32>,
    back_color: vec4<f32>,
    // x: 1 = flat shading, y: 1 = encode sRGB in the shader (non-sRGB target),
    // z: 1 = orthographic, w: headlight intensity
    params: vec4<f32>,
    // x: line pull towards the camera (fraction of view depth, perspective),
    // y: the same in world units (orthographic), z: 1 = the colour attribute
    // holds texture coordinates (checker texture), w: 1 = the wireframe pipeline
    // takes per-vertex colours (or texture coordinates) from `mesh_colors`
    line: vec4<f32>,
    // the wireframe: x = line width in pixels, y = highest edge generation
    // drawn, z: 1 = wire only (the faces are not shaded), w = strength of
    // the darkening over shaded faces
    wire: vec4<f32>,
    // x, y: the viewport's size in pixels, z: the radius of dots in pixels,
    // w: the viewport's top row in the target
    viewport: vec4<f32>,
    // zebra and isophotes (params.x 3 and 4): x = stripe count, y = the
    // light bars' angle from vertical on the screen (radians)
    stripes: vec4<f32>,
    // curvature values (render/mod.rs: Look::values): x: 1 = the colour
    // attribute holds (t, e, 0), t the value over the colour range's
    // half-width and e 1 where evaluated (0: grey), mapped per pixel on the
    // diverging map; y = isolines per side of zero (0: none), z = their
    // width in pixels
    contour: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: View;

struct LineStyle { color: vec4<f32> };
@group(1) @binding(0) var<uniform> style: LineStyle;

struct MeshOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
};

fn mesh_vertex(pos: vec3<f32>, normal: vec3<f32>, color: vec3<f32>) -> MeshOut {
    var o: MeshOut;
    o.clip = u.proj * (u.view * vec4<f32>(pos, 1.0));
    o.world = pos;
    o.normal = normal;
    o.color = color;
    return o;
}

@vertex
fn vs_mesh(@location(0) pos: vec3<f32>, @location(1) normal: vec3<f32>) -> MeshOut {
    return mesh_vertex(pos, normal, u.front_color.rgb);
}

// Per-vertex colours (level shells, displacement maps) replace the front colour.
@vertex
fn vs_mesh_colored(@location(0) pos: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) color: vec3<f32>) -> MeshOut {
    return mesh_vertex(pos, normal, color);
}

fn encode_srgb(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

fn finish(c: vec3<f32>) -> vec4<f32> {
    let k = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
    if u.params.y > 0.5 {
        return vec4<f32>(encode_srgb(k), 1.0);
    }
    return vec4<f32>(k, 1.0);
}

fn light(n: vec3<f32>, v: vec3<f32>, l: vec3<f32>, intensity: f32, base: vec3<f32>) -> vec3<f32> {
    let d = max(dot(n, l), 0.0);
    let h = normalize(l + v);
    let s = select(0.0, pow(max(dot(n, h), 0.0), 48.0), d > 0.0);
    return intensity * (0.75 * d * base + vec3<f32>(0.35 * s));
}

// The lit colour (linear RGB) of a fragment at `world` with the interpolated
// `normal` and base colour `color` (or texture coordinates, for the checker).
fn shade(world: vec3<f32>, normal: vec3<f32>, color: vec3<f32>, front: bool) -> vec3<f32> {
    var v: vec3<f32>;
    if u.params.z > 0.5 {
        v = -normalize(u.forward.xyz);
    } else {
        v = normalize(u.eye.xyz - world);
    }
    var n: vec3<f32>;
    if abs(u.params.x - 1.0) < 0.5 {
        n = cross(dpdx(world), dpdy(world));
        let len = length(n);
        n = select(v, n / len, len > 1e-20);
        if dot(n, v) < 0.0 {
            n = -n;
        }
    } else {
        let len = length(normal);
        n = select(v, normal / len, len > 1e-20);
        if !front {
            n = -n;
        }
    }
    var front_base = color;
    if u.contour.x > 0.5 {
        front_base = value_color(color);
    }
    if u.line.z > 0.5 {
        // Checker texture from the interpolated texture coordinates (8 x 8 squares per unit).
        let cell = floor(color.xy * 8.0);
        let odd = (i32(cell.x) + i32(cell.y)) & 1;
        front_base = select(vec3<f32>(0.85, 0.85, 0.8), vec3<f32>(0.08, 0.12, 0.35), odd == 1);
    }
    let base = select(u.back_color.rgb, front_base, front);
    if u.params.x > 2.5 {
        return stripes(n, v, u.params.x > 3.5, front);
    }
    if u.params.x > 1.5 {
        return studio(n, base, front);
    }
    // The headlight shines from the eye along the view direction (l = v), so a face
    // seen head-on gets its full diffuse and specular; the key and fill lights,
    // fixed in the world, give silhouettes their shape.
    var c = 0.12 * base;
    c += light(n, v, v, u.params.w, base);
    c += light(n, v, normalize(u.key_light.xyz), u.key_light.w, base);
    c += light(n, v, normalize(u.fill_light.xyz), u.fill_light.w, base);
    return c;
}

// Studio (a procedural matcap): the normal in view space looks up clay lit
// by a soft key light above left, a cool sky above and a warm bounce
// below, a broad highlight and a rim, all fixed to the camera.
fn studio(n_world: vec3<f32>, base: vec3<f32>, front: bool) -> vec3<f32> {
    let n = normalize((u.view * vec4<f32>(n_world, 0.0)).xyz);
    let clay = select(base, vec3<f32>(0.58, 0.54, 0.5), front && u.line.z < 0.5 && u.line.w < 0.5);
    let sky = mix(vec3<f32>(0.32, 0.26, 0.22), vec3<f32>(0.7, 0.78, 0.9), 0.5 + 0.5 * n.y);
    let key = max(dot(n, normalize(vec3<f32>(-0.45, 0.6, 0.65))), 0.0);
    let high = pow(max(dot(n, normalize(vec3<f32>(-0.3, 0.45, 0.85))), 0.0), 24.0);
    let rim = pow(1.0 - clamp(n.z, 0.0, 1.0), 3.0);
    return clay * (0.35 * sky + 0.75 * key) + vec3<f32>(0.22 * high) + 0.25 * rim * vec3<f32>(0.75, 0.82, 0.95);
}

// Reflection lines (zebra) and isophotes, per pixel from the normal, in
// view space so the environment turns with the camera. Zebra: the surface
// mirrors a ring of parallel light bars around the object, their axis in the
// screen plane at u.stripes.y from vertical; the reflected view direction
// r = reflect(-v, n) is seen at azimuth atan2(r . across, r . z) around that
// axis, and u.stripes.x bars fill the turn, so the stripes follow the normal
// and a jump in it is a jump in the stripes, a jump in curvature a kink.
// Isophotes: bands of equal angle acos(n . v), from facing the eye to
// grazing. Stripe edges are anti-aliased over about one pixel (fwidth).
fn stripes(n_world: vec3<f32>, v_world: vec3<f32>, isophote: bool, front: bool) -> vec3<f32> {
    let n = normalize((u.view * vec4<f32>(n_world, 0.0)).xyz);
    let v = normalize((u.view * vec4<f32>(v_world, 0.0)).xyz);
    let r = reflect(-v, n);
    let across = vec3<f32>(cos(u.stripes.y), -sin(u.stripes.y), 0.0);
    let azimuth = atan2(dot(r, across), r.z) / 6.2831853 + 0.5;
    let facing = acos(clamp(dot(n, v), -1.0, 1.0)) * 2.0 / 3.14159265;
    let t = select(azimuth, facing, isophote) * u.stripes.x;
    // the seam of atan2 behind the object would blur one pixel row: ignore
    // derivatives of a whole period or more
    let w = clamp(fwidth(t), 1e-4, 0.5);
    // light where the phase is within a quarter period of a band's middle
    let light = clamp((abs(fract(t) - 0.5) - 0.25) / w + 0.5, 0.0, 1.0);
    let ink = mix(vec3<f32>(0.02, 0.02, 0.025), vec3<f32>(0.92, 0.92, 0.9), light);
    return select(ink * vec3<f32>(0.75, 0.6, 0.5), ink, front);
}

// Blue (-1) through white (0) to red (+1), linear RGB; the same map as
// diverging() in src/subdiv/eval/color.rs.
fn diverging(t: f32) -> vec3<f32> {
    let s = clamp(t, -1.0, 1.0);
    let white = vec3<f32>(0.92);
    return select(mix(white, vec3<f32>(0.75, 0.06, 0.05), s), mix(white, vec3<f32>(0.05, 0.18, 0.75), -s), s < 0.0);
}

// The colour of a value attribute (t, e, 0) (see View.contour): mid grey
// where not evaluated (e = 0), blending into the map across the triangles
// that touch such a vertex; t / e is the mean of the evaluated corners.
fn value_color(c: vec3<f32>) -> vec3<f32> {
    let e = clamp(c.y, 0.0, 1.0);
    return mix(vec3<f32>(0.45), diverging(c.x / max(e, 1e-6)), e);
}

// Isolines of the value over a shaded colour `c`: zero and N levels on
// each side (N = contour.y), at every multiple of 1 / (N + 1) of the
// range's half-width, short of its ends (where the clamped extremes would
// draw ragged loops); the zero level twice as wide and darker. With
// s = N + 1, the distance in pixels to the nearest level is
// |ts - round(ts)| / fwidth(ts), so the lines keep their width in pixels
// at any zoom and fade over about a pixel (no stairs). Only where all
// three corners were evaluated (e = 1).
fn isolines(c: vec3<f32>, value: vec3<f32>, front: bool) -> vec3<f32> {
    if u.contour.x < 0.5 || u.contour.y < 0.5 || u.params.x > 2.5 {
        return c;
    }
    let n = u.contour.y;
    let v = value.x * (n + 1.0);
    let w = max(fwidth(v), 1e-6);
    let k = round(v);
    let zero = k == 0.0;
    let half = 0.5 * u.contour.z * select(1.0, 2.0, zero);
    let d = abs(v - k) / w;
    // where the levels crowd (grazing angles, steep values) closer than a
    // few line widths they fade out instead of blackening the colours
    let spacing = 1.0 / (w * u.contour.z);
    let line = (1.0 - smoothstep(half - 0.5, half + 0.75, d)) * smoothstep(1.2, 2.4, spacing);
    let shown = front && value.y > 0.999 && abs(k) <= n;
    let a = select(0.0, line, shown);
    let ink = c * select(0.25, 0.05, zero);
    return mix(c, ink, a);
}

// The background: one triangle over the whole viewport, a quiet vertical
// gradient (render/scene.rs: BACKGROUND_TOP to BACKGROUND_BOTTOM, linear).
@vertex
fn vs_background(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.5, 1.0);
}

@fragment
fn fs_background(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let t = clamp((p.y - u.viewport.w) / max(u.viewport.y, 1.0), 0.0, 1.0);
    return finish(mix(vec3<f32>(0.075, 0.08, 0.1), vec3<f32>(0.025, 0.027, 0.036), t));
}

@fragment
fn fs_mesh(i: MeshOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return finish(isolines(shade(i.world, i.normal, i.color, front), i.color, front));
}

// Lines are pulled towards the eye so they win the depth test against the
// faces they lie on. Scaling about the eye (perspective) keeps their screen position.
fn line_clip(pos: vec3<f32>) -> vec4<f32> {
    var p = u.view * vec4<f32>(pos, 1.0);
    if u.params.z > 0.5 {
        p.z += u.line.y;
    } else {
        p = vec4<f32>(p.xyz * (1.0 - u.line.x), 1.0);
    }
    return u.proj * p;
}

@vertex
fn vs_line(@location(0) pos: vec3<f32>) -> @builtin(position) vec4<f32> {
    return line_clip(pos);
}

@fragment
fn fs_line() -> @location(0) vec4<f32> {
    return vec4<f32>(finish(style.color.rgb).rgb, style.color.a);
}

// The cage where the surface hides it: the same lines, faint (no depth test).
@fragment
fn fs_line_hidden() -> @location(0) vec4<f32> {
    return vec4<f32>(finish(style.color.rgb).rgb, 0.3);
}

// Dots: a quad of two triangles per point (instance), a constant size in
// pixels, pulled towards the eye like the lines; round with a smooth rim.
struct DotOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) local: vec2<f32>,
};

@vertex
fn vs_dot(@builtin(vertex_index) i: u32, @location(0) pos: vec3<f32>) -> DotOut {
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, 1.0), vec2<f32>(-1.0, 1.0),
    );
    let k = corners[i];
    var o: DotOut;
    let c = line_clip(pos);
    // one pixel more than the radius, for the rim's smoothstep
    let r = u.viewport.z + 1.0;
    o.clip = c + vec4<f32>(k * r * 2.0 / max(u.viewport.xy, vec2<f32>(1.0)) * c.w, 0.0, 0.0);
    o.local = k * r;
    return o;
}

fn dot_alpha(local: vec2<f32>) -> f32 {
    return 1.0 - smoothstep(u.viewport.z - 0.75, u.viewport.z + 0.5, length(local));
}

@fragment
fn fs_dot(i: DotOut) -> @location(0) vec4<f32> {
    return vec4<f32>(finish(style.color.rgb).rgb, dot_alpha(i.local));
}

@fragment
fn fs_dot_hidden(i: DotOut) -> @location(0) vec4<f32> {
    return vec4<f32>(finish(style.color.rgb).rgb, 0.3 * dot_alpha(i.local));
}

// ---- The single-pass wireframe --------------------------------------------
//
// Drawn without an index buffer: vertex `i` of the draw is corner `i` of the
// corner table, whose vertex, position, normal and edge generation are read
// from storage buffers. Each corner carries the barycentric coordinate that
// is 1 at itself and 0 on the edge opposite it, so in the fragment shader
// b_k / fwidth(b_k) is the distance in pixels to the edge opposite corner k:
// the line is drawn where it is below half the width, with a smoothstep over
// about a pixel (anti-aliasing, no MSAA needed). The faces themselves hide the
// lines behind them (the depth test of the same pass), and no line is drawn
// twice or needs a depth offset.
//
// Edges are filtered by generation (the level at which they were made: 0 on
// the control mesh's edges): an edge is drawn when its generation is at most
// wire.y. Density: where the shown lines would be closer than a few pixels
// they fade out (the spacing of an edge of generation g in a level-L mesh is
// the triangle's altitude, 1 / fwidth(b), times 2^(L - g)): a fine mesh keeps
// its shading and shows its coarser generations, down to the control edges.
// A line is drawn by the two triangles along it only, so where it passes a
// vertex the triangles that only touch that vertex would cut it; each
// vertex on a shown edge is drawn as a disk too (its distance from the
// fragment solved from the barycentric gradients), which closes the gaps.
// Over shaded faces a line darkens the colour (lightens it on dark faces)
// instead of painting it over.

@group(2) @binding(0) var<storage, read> mesh_positions: array<f32>;
@group(2) @binding(1) var<storage, read> mesh_normals: array<f32>;
@group(2) @binding(2) var<storage, read> mesh_corners: array<u32>;
// per triangle t, one word: for its corner k, the generation of the edge
// opposite it at bit 5k and the lowest generation of the edges at its
// vertex at bit 15 + 5k (five bits each)
@group(2) @binding(3) var<storage, read> mesh_generations: array<u32>;
@group(2) @binding(4) var<storage, read> mesh_colors: array<f32>;

// Without per-vertex colours (the usual case) the wire carries no colour
// varying: the fragment takes the front colour from the uniforms. On a
// software rasteriser, where every attribute costs set-up per triangle and a
// dense mesh has more triangles than pixels, that is a tenth of the frame.
struct WireOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    // barycentrics b0 and b1 (b2 = 1 - b0 - b1: one attribute less to set
    // up per triangle)
    @location(3) bary: vec2<f32>,
    // the triangle's generations word (see mesh_generations), the same at
    // its three corners; the fragment shader turns it into line spacings
    @location(4) @interpolate(flat) generations: u32,
};

// The same with per-vertex colours (or texture coordinates) from mesh_colors.
struct WireColoredOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
    @location(3) bary: vec2<f32>,
    @location(4) @interpolate(flat) generations: u32,
};

// Per edge (opposite corner k) and per vertex (corner k) of a triangle
// whose generations word is w: 0 = not drawn, else the spacing of the edges
// of its generation in altitudes of this triangle, 2^(level - g). Computed
// per fragment rather than per vertex: a dense mesh has fewer fragments
// than the three vertices per triangle of the wire's draw.
fn spacings(w: u32) -> array<vec3<f32>, 2> {
    let e = vec3<u32>(w & 31u, (w >> 5u) & 31u, (w >> 10u) & 31u);
    let v = vec3<u32>((w >> 15u) & 31u, (w >> 20u) & 31u, (w >> 25u) & 31u);
    // generation 31: a diagonal inside a polygon (a triangulated quad), never drawn
    let hidden = e == vec3<u32>(31u);
    let real = select(e, vec3<u32>(0u), hidden);
    // every triangle of a split level has an edge of that level (its inner one)
    let level = vec3<f32>(f32(max(real.x, max(real.y, real.z))));
    let most = vec3<u32>(u32(u.wire.y));
    let se = select(vec3<f32>(0.0), exp2(level - vec3<f32>(e)), (e <= most) & !hidden);
    let sv = select(vec3<f32>(0.0), exp2(level - vec3<f32>(v)), v <= most);
    return array<vec3<f32>, 2>(se, sv);
}

fn fetch3(which: u32, i: u32) -> vec3<f32> {
    if which == 0u {
        return vec3<f32>(mesh_positions[3u * i], mesh_positions[3u * i + 1u], mesh_positions[3u * i + 2u]);
    }
    if which == 1u {
        return vec3<f32>(mesh_normals[3u * i], mesh_normals[3u * i + 1u], mesh_normals[3u * i + 2u]);
    }
    return vec3<f32>(mesh_colors[3u * i], mesh_colors[3u * i + 1u], mesh_colors[3u * i + 2u]);
}

fn wire_vertex(c: u32, v: u32) -> WireOut {
    let m = mesh_vertex(fetch3(0u, v), fetch3(1u, v), vec3<f32>(0.0));
    var o: WireOut;
    o.clip = m.clip;
    o.world = m.world;
    o.normal = m.normal;
    let k = c % 3u;
    o.bary = vec2<f32>(f32(k == 0u), f32(k == 1u));
    o.generations = mesh_generations[c / 3u];
    return o;
}

@vertex
fn vs_wire(@builtin(vertex_index) c: u32) -> WireOut {
    return wire_vertex(c, mesh_corners[c]);
}

@vertex
fn vs_wire_colored(@builtin(vertex_index) c: u32) -> WireColoredOut {
    let v = mesh_corners[c];
    let w = wire_vertex(c, v);
    var o: WireColoredOut;
    o.clip = w.clip;
    o.world = w.world;
    o.normal = w.normal;
    o.color = fetch3(2u, v);
    o.bary = w.bary;
    o.generations = w.generations;
    return o;
}

// Coverage of the wire at this fragment (0..1): per shown edge, the line
// faded by the spacing of the edges of its generation, so where the finest
// edges would crowd, the coarser generations (down to the control edges)
// remain.
fn wire_coverage(bary: vec3<f32>, spacing: vec3<f32>, vertex_spacing: vec3<f32>) -> f32 {
    let gx = dpdx(bary);
    let gy = dpdy(bary);
    let fw = max(abs(gx) + abs(gy), vec3<f32>(1e-6));
    // the triangle's size in pixels, sqrt(2 area): the Jacobian of two
    // barycentrics over the screen is 1 / (2 area); steadier from one
    // triangle to the next than the smallest altitude, so a line does not
    // flicker along its length
    let jac = gx.x * gy.y - gy.x * gx.y;
    let size = inverseSqrt(max(abs(jac), 1e-12));
    // distances in pixels: to the edge opposite each corner, and to each
    // corner (the screen offset d from corner k solves grad(b_i) . d = b_i
    // for the other two, whose barycentrics are 0 at k)
    let to_edge = bary / fw;
    let inv = 1.0 / select(jac, 1e-12, abs(jac) < 1e-12);
    // from corner 2: grad b0 . d = b0, grad b1 . d = b1
    let d2 = vec2<f32>(bary.x * gy.y - gy.x * bary.y, gx.x * bary.y - bary.x * gx.y) * inv;
    // the offsets from corners 0 and 1 differ by the edge vectors, which
    // are the offsets of those corners from corner 2: e = d2 at b = (1,0,0)
    let e0 = vec2<f32>(gy.y, -gx.y) * inv;
    let e1 = vec2<f32>(-gy.x, gx.x) * inv;
    let to_vertex = vec3<f32>(length(d2 - e0), length(d2 - e1), length(d2));
    let half = 0.5 * u.wire.x;
    let ramp0 = vec3<f32>(half - 0.5);
    let ramp1 = vec3<f32>(half + 0.75);
    let line = vec3<f32>(1.0) - smoothstep(ramp0, ramp1, to_edge);
    let disk = vec3<f32>(1.0) - smoothstep(ramp0, ramp1, to_vertex);
    // (wire only keeps a trace of the densest lines, or nothing would show)
    let least = vec3<f32>(select(0.0, 0.25, u.wire.z > 0.5));
    let near = vec3<f32>(2.5 * u.wire.x);
    let far = vec3<f32>(9.0 * u.wire.x);
    let fade = max(smoothstep(near, far, spacing * size), least);
    let vfade = max(smoothstep(near, far, vertex_spacing * size), least);
    let a = select(vec3<f32>(0.0), line * fade, spacing > vec3<f32>(0.0));
    let v = select(vec3<f32>(0.0), disk * vfade, vertex_spacing > vec3<f32>(0.0));
    return max(max(a.x, max(a.y, a.z)), max(v.x, max(v.y, v.z)));
}

// The faces with their wire: `color` is the base colour (or texture
// coordinates) of the face at this fragment.
fn wire_fragment(world: vec3<f32>, normal: vec3<f32>, color: vec3<f32>, b: vec2<f32>, generations: u32, front: bool) -> vec4<f32> {
    let s = spacings(generations);
    let a = wire_coverage(vec3<f32>(b, 1.0 - b.x - b.y), s[0], s[1]);
    if u.wire.z > 0.5 {
        // wire only: light lines over the background (blended), the face
        // still writes depth and so hides the lines behind it
        let ink = select(vec3<f32>(0.55, 0.5, 0.45), vec3<f32>(0.80, 0.84, 0.92), front);
        return vec4<f32>(finish(ink).rgb, a);
    }
    let c = clamp(isolines(shade(world, normal, color, front), color, front), vec3<f32>(0.0), vec3<f32>(1.0));
    let lum = dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
    // darken lit faces, lighten faces in shadow
    let ink = select(c * 0.2, mix(c, vec3<f32>(0.75, 0.8, 0.9), 0.55), lum < 0.06);
    return finish(mix(c, ink, a * u.wire.w));
}

@fragment
fn fs_wire(i: WireOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return wire_fragment(i.world, i.normal, u.front_color.rgb, i.bary, i.generations, front);
}

@fragment
fn fs_wire_colored(i: WireColoredOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return wire_fragment(i.world, i.normal, i.color, i.bary, i.generations, front);
}

// ---- Materials ------------------------------------------------------------
//
// One material group at a time (render/textures.rs): the base colour of a
// fragment is the material's factor (MTL Kd, glTF baseColorFactor) times
// its texture sampled at the interpolated texture coordinate, which the
// colour attribute carries as (u, v, 0). The texture is sRGB, so the
// sample is linear light, filtered between texels and between mipmap
// levels; v points up from the image's bottom row (OBJ's convention), the
// texture's rows run down. Materials without a texture bind a white texel
// and clear flags.x.

struct SurfaceMaterial {
    factor: vec4<f32>,
    // x: 1 = the texture is sampled
    flags: vec4<f32>,
};

@group(3) @binding(0) var material_texture: texture_2d<f32>;
@group(3) @binding(1) var material_sampler: sampler;
@group(3) @binding(2) var<uniform> surface_material: SurfaceMaterial;

fn material_color(uv: vec2<f32>) -> vec3<f32> {
    let t = textureSample(material_texture, material_sampler, vec2<f32>(uv.x, 1.0 - uv.y)).rgb;
    return surface_material.factor.rgb * select(vec3<f32>(1.0), t, surface_material.flags.x > 0.5);
}

@fragment
fn fs_mesh_textured(i: MeshOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return finish(shade(i.world, i.normal, material_color(i.color.xy), front));
}

@fragment
fn fs_wire_textured(i: WireColoredOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    return wire_fragment(i.world, i.normal, material_color(i.color.xy), i.bary, i.generations, front);
}

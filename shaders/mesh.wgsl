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
    // holds texture coordinates (checker texture)
    line: vec4<f32>,
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

@fragment
fn fs_mesh(i: MeshOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var v: vec3<f32>;
    if u.params.z > 0.5 {
        v = -normalize(u.forward.xyz);
    } else {
        v = normalize(u.eye.xyz - i.world);
    }
    var n: vec3<f32>;
    if u.params.x > 0.5 {
        n = cross(dpdx(i.world), dpdy(i.world));
        let len = length(n);
        n = select(v, n / len, len > 1e-20);
        if dot(n, v) < 0.0 {
            n = -n;
        }
    } else {
        let len = length(i.normal);
        n = select(v, i.normal / len, len > 1e-20);
        if !front {
            n = -n;
        }
    }
    var front_base = i.color;
    if u.line.z > 0.5 {
        // Checker texture from the interpolated texture coordinates (8 x 8 squares per unit).
        let cell = floor(i.color.xy * 8.0);
        let odd = (i32(cell.x) + i32(cell.y)) & 1;
        front_base = select(vec3<f32>(0.85, 0.85, 0.8), vec3<f32>(0.08, 0.12, 0.35), odd == 1);
    }
    let base = select(u.back_color.rgb, front_base, front);
    // The headlight shines from the eye along the view direction (l = v), so a face
    // seen head-on gets its full diffuse and specular; the key and fill lights,
    // fixed in the world, give silhouettes their shape.
    var c = 0.12 * base;
    c += light(n, v, v, u.params.w, base);
    c += light(n, v, normalize(u.key_light.xyz), u.key_light.w, base);
    c += light(n, v, normalize(u.fill_light.xyz), u.fill_light.w, base);
    return finish(c);
}

// A depth-only pass uses vs_mesh with no colour writes (hidden-line wireframe).

@vertex
fn vs_line(@location(0) pos: vec3<f32>) -> @builtin(position) vec4<f32> {
    var p = u.view * vec4<f32>(pos, 1.0);
    // Pull lines towards the eye so they win the depth test against the faces
    // they lie on. Scaling about the eye (perspective) keeps their screen position.
    if u.params.z > 0.5 {
        p.z += u.line.y;
    } else {
        p = vec4<f32>(p.xyz * (1.0 - u.line.x), 1.0);
    }
    return u.proj * p;
}

@fragment
fn fs_line() -> @location(0) vec4<f32> {
    return finish(style.color.rgb);
}

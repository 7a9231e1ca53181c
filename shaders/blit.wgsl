// Copies a rendered scene texture onto the window, pixel for pixel (the
// surface may not allow copies, so this is a full-screen triangle).
@group(0) @binding(0) var scene: texture_2d<f32>;

@vertex
fn vs_blit(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    return vec4<f32>(x * 2.0 - 1.0, 1.0 - y * 2.0, 0.0, 1.0);
}

@fragment
fn fs_blit(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(scene, vec2<i32>(p.xy), 0);
}

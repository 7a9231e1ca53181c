// Animation on the GPU (src/render/gpu_anim.rs): one `level` dispatch per
// recorded level of a stencil plan (CSR rows: offsets, indices, weights; the
// same rows as StencilPlan's CPU evaluation), then `normals` over the finest
// level's one-rings. Positions and normals are tightly packed f32 triples
// (array<vec3<f32>> would have a 16-byte stride), so the last level writes
// straight into the vertex buffers the renderer draws.

struct Params {
    // vertices copied unchanged (interpolating schemes), then `rows` stencil rows
    copied: u32,
    rows: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> prm: Params;
@group(0) @binding(1) var<storage, read> src: array<f32>;
@group(0) @binding(2) var<storage, read> offsets: array<u32>;
@group(0) @binding(3) var<storage, read> indices: array<u32>;
@group(0) @binding(4) var<storage, read> weights: array<f32>;
@group(0) @binding(5) var<storage, read_write> dst: array<f32>;

fn at(j: u32) -> vec3<f32> {
    return vec3<f32>(src[3u * j], src[3u * j + 1u], src[3u * j + 2u]);
}

// dispatches are 2D when one dimension would exceed 65535 workgroups
fn thread(gid: vec3<u32>, groups: vec3<u32>) -> u32 {
    return gid.x + gid.y * groups.x * 64u;
}

@compute @workgroup_size(64)
fn level(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread(gid, groups);
    if (i >= prm.copied + prm.rows) {
        return;
    }
    var s = vec3<f32>(0.0);
    if (i < prm.copied) {
        s = at(i);
    } else {
        let r = i - prm.copied;
        for (var k = offsets[r]; k < offsets[r + 1u]; k++) {
            s += at(indices[k]) * weights[k];
        }
    }
    dst[3u * i] = s.x;
    dst[3u * i + 1u] = s.y;
    dst[3u * i + 2u] = s.z;
}

// normals: `offsets`/`indices` are the one-rings (a closed ring repeats its
// first neighbour at the end), `src` the finest positions, `dst` the normals;
// the faces around v are (v, r_k, r_k+1): the area-weighted normal is
// sum (r_k - v) x (r_k+1 - v), as mesh::normals::VertexRings on the CPU.
@compute @workgroup_size(64)
fn normals(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let v = thread(gid, groups);
    if (v >= prm.rows) {
        return;
    }
    let p = at(v);
    var s = vec3<f32>(0.0);
    let a = offsets[v];
    let b = offsets[v + 1u];
    if (b > a) {
        var prev = at(indices[a]) - p;
        for (var k = a + 1u; k < b; k++) {
            let d = at(indices[k]) - p;
            s += cross(prev, d);
            prev = d;
        }
    }
    let l = length(s);
    var n = vec3<f32>(0.0, 0.0, 1.0);
    if (l > 0.0) {
        n = s / l;
    }
    dst[3u * v] = n.x;
    dst[3u * v + 1u] = n.y;
    dst[3u * v + 2u] = n.z;
}

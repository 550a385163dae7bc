//! rastty against a peer: the `euc` crate (a software rasterizer in Rust)
//! draws the same mesh, turned the same way, on the same sample grid
//! (200×120 samples: 200×60 cells in half mode), with a depth buffer, back
//! faces culled and per-vertex lighting interpolated. rastty's frame also
//! includes what euc does not do: the blit into 12,000 terminal cells.
//! euc snaps nothing and has no tie rule; rastty's path is exact.
//!
//! `cargo bench --bench euc`

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use euc::{Pipeline, Target, buffer::Buffer2d, rasterizer};
use glam::{Mat4, Vec3};
use rastty::{ColorDepth, GlyphMode, RenderOptions, Renderer, Scene};

/// The mesh drawn by euc as rastty draws it: the vertex shader transforms
/// and lights each vertex (Gouraud, the same Lambert term), the fragment
/// shader packs the interpolated colour.
struct Lit<'a> {
    mvp: Mat4,
    normal: glam::Mat3,
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    lights: rastty::shade::Lights,
}

impl Pipeline for Lit<'_> {
    type Vertex = u32;
    type VsOut = (f32, f32, f32);
    type Pixel = u32;

    #[inline(always)]
    fn vert(&self, i: &u32) -> ([f32; 4], Self::VsOut) {
        let i = *i as usize;
        let c = self.mvp * self.positions[i].extend(1.0);
        let l = self
            .lights
            .lambert((self.normal * self.normals[i]).normalize_or_zero())
            * 0.8;
        // euc keeps the smaller z; rastty's canonical cube has larger z
        // nearer.
        (
            [c.x, c.y, -c.z, c.w],
            (l.x.min(1.0), l.y.min(1.0), l.z.min(1.0)),
        )
    }

    #[inline(always)]
    fn frag(&self, c: &Self::VsOut) -> u32 {
        ((c.0 * 255.0) as u32) << 16 | ((c.1 * 255.0) as u32) << 8 | (c.2 * 255.0) as u32
    }
}

fn vs_euc(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let scene = Scene::of_model(Path::new(&format!("{root}/tests/models/bunny.obj"))).unwrap();
    let opts = RenderOptions {
        cols: 200,
        rows: 60,
        glyphs: GlyphMode::Half,
        color: ColorDepth::TrueColor,
        turn: Vec3::new(10.0, 30.0, 0.0),
        ..RenderOptions::default()
    };
    let mut group = c.benchmark_group("vs-euc");
    let mut r = Renderer::new();
    group.bench_function("rastty/bunny/200x120-samples", |b| {
        b.iter(|| r.render(&scene, &opts).cols())
    });

    // The same transform and the same lights for euc.
    let mesh = &scene.meshes[0];
    let model = rastty::transform::rotation(opts.turn) * mesh.model;
    let mvp = scene.camera.view_projection(opts.aspect()) * model;
    let indices: Vec<u32> = mesh.faces.iter().flatten().copied().collect();
    let pipeline = Lit {
        mvp,
        normal: glam::Mat3::from_mat4(model).inverse().transpose(),
        positions: &mesh.positions,
        normals: &mesh.normals,
        lights: rastty::shade::Lights::new(&scene.lights),
    };
    let mut color = Buffer2d::new([200, 120], 0u32);
    let mut depth = Buffer2d::new([200, 120], 1.0f32);
    group.bench_function("euc/bunny/200x120-samples", |b| {
        b.iter(|| {
            color.clear(0);
            depth.clear(1.0);
            pipeline.draw::<rasterizer::Triangles<_, rasterizer::BackfaceCullingEnabled>, _>(
                &indices,
                &mut color,
                Some(&mut depth),
            );
        })
    });
    // How much each drew, for the record.
    r.render(&scene, &opts);
    let ours = r
        .framebuffer()
        .samples()
        .iter()
        .filter(|s| s.is_some())
        .count();
    let theirs = color.as_ref().iter().filter(|&&p| p != 0).count();
    eprintln!("samples drawn: rastty {ours}, euc {theirs}");
    group.finish();
}

criterion_group!(benches, vs_euc);
criterion_main!(benches);

//! The bunny as euc draws it, for `vs_euc`.

use euc::{Pipeline, Target, buffer::Buffer2d, rasterizer};
use glam::{Mat4, Vec3};
use rastty::{RenderOptions, scene::Scene};

/// The mesh drawn by euc as rastty draws it: the vertex shader transforms
/// and lights each vertex (Gouraud, the same Lambert term), the fragment
/// shader packs the interpolated colour.
pub struct Lit<'a> {
    mvp: Mat4,
    normal: glam::Mat3,
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    lights: rastty::Lights,
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

/// The frame both draw: the bunny's 200×60 cells in half mode (200×120
/// samples), turned a little.
pub fn options() -> RenderOptions {
    RenderOptions {
        cols: 200,
        rows: 60,
        glyphs: rastty::GlyphMode::Half,
        color: rastty::color::ColorDepth::TrueColor,
        turn: Vec3::new(10.0, 30.0, 0.0),
        ..RenderOptions::default()
    }
}

/// What euc needs to draw `scene`'s first mesh as rastty draws it with
/// `opts`: the pipeline, the index list, and colour and depth buffers.
pub fn setup<'a>(
    scene: &'a Scene,
    opts: &RenderOptions,
) -> (Lit<'a>, Vec<u32>, Buffer2d<u32>, Buffer2d<f32>) {
    let mesh = &scene.meshes[0];
    let model = rastty::transform::rotation(opts.turn) * mesh.model;
    // The camera as rastty places it for this view and turn (a framing
    // camera's distance depends on the aspect and on the turn's tilt).
    let camera = scene
        .camera
        .resolved_turning(opts.aspect(), opts.turn, opts.turn_axis);
    let mvp = camera.view_projection(opts.aspect()) * model;
    let indices: Vec<u32> = mesh.faces.iter().flatten().copied().collect();
    let pipeline = Lit {
        mvp,
        normal: glam::Mat3::from_mat4(model).inverse().transpose(),
        positions: &mesh.positions,
        normals: &mesh.normals,
        lights: rastty::Lights::new(&scene.lights),
    };
    let grid = opts.grid();
    let size = [grid.width as usize, grid.height as usize];
    (
        pipeline,
        indices,
        Buffer2d::new(size, 0u32),
        Buffer2d::new(size, 1.0f32),
    )
}

/// One euc frame: clear, then draw with depth test and back faces culled.
pub fn frame(
    pipeline: &Lit,
    indices: &[u32],
    color: &mut Buffer2d<u32>,
    depth: &mut Buffer2d<f32>,
) {
    color.clear(0);
    depth.clear(1.0);
    pipeline.draw::<rasterizer::Triangles<_, rasterizer::BackfaceCullingEnabled>, _>(
        indices,
        color,
        Some(depth),
    );
}

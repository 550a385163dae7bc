//! The interpolation and texture-filtering knobs: a floor running away
//! from the eye, against an f64 ray cast and a supersampled reference.

use super::*;

/// A floor from 1 to 8 units in front of the eye, red near, blue far:
/// every drawn sample's colour against the colour of the floor point behind
/// it, found by casting the ray in f64. Largest and mean error, 0–255 in
/// linear light (where colours are interpolated).
pub fn interpolation_error(interpolation: Interpolation) -> (f64, f64) {
    let near = Vec3::new(0.0, -1.0, -1.0);
    let far = Vec3::new(0.0, -1.0, -8.0);
    let camera = Camera {
        shift: rastty::glam::Vec2::ZERO,
        projection: Projection::Perspective {
            fov_y: 90.0,
            near: 0.5,
            far: 20.0,
        },
        eye: Vec3::ZERO,
        target: Vec3::new(0.0, 0.0, -1.0),
        up: Vec3::Y,
        fit: None,
    };
    let (l, r) = (Vec3::X * 3.0, Vec3::X * -3.0);
    let (red, blue) = (Rgb::new(255, 0, 0), Rgb::new(0, 0, 255));
    let scene = Scene {
        camera,
        triangles: vec![
            Triangle {
                vertices: [near + r, near + l, far + l],
                color: TriangleColor::PerVertex([red, red, blue]),
            },
            Triangle {
                vertices: [near + r, far + l, far + r],
                color: TriangleColor::PerVertex([red, blue, blue]),
            },
        ],
        ..Scene::default()
    };
    let opts = RenderOptions {
        cols: 64,
        rows: 32,
        glyphs: GlyphMode::Block,
        interpolation,
        cell_aspect: 1.0,
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    renderer.render(&scene, &opts);
    let fb = renderer.framebuffer();
    let grid = fb.grid();
    let inv = camera.view_projection(opts.aspect()).as_dmat4().inverse();
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in 0..grid.height {
        for x in 0..grid.width {
            let Some(c) = fb.get(x, y) else { continue };
            let ndc = |v: u32, n: u32| (v as f64 + 0.5) / n as f64 * 2.0 - 1.0;
            let p0 = inv.project_point3(glam::DVec3::new(
                ndc(x, grid.width),
                ndc(y, grid.height),
                1.0,
            ));
            let p1 = inv.project_point3(glam::DVec3::new(
                ndc(x, grid.width),
                ndc(y, grid.height),
                -1.0,
            ));
            let t = (-1.0 - p0.y) / (p1.y - p0.y);
            let s = ((p0.z + t * (p1.z - p0.z)) + 1.0) / -7.0;
            // Colours interpolate in linear light: compared there, in
            // 0–255 units.
            let want = [255.0 * (1.0 - s), 0.0, 255.0 * s];
            let got = c.to_f32().map(|v| v / 257.0);
            let e = (0..3)
                .map(|k| (got[k] as f64 - want[k]).abs())
                .fold(0.0, f64::max);
            max = max.max(e);
            sum += e;
            n += 1;
        }
    }
    (max, sum / n.max(1) as f64)
}

/// The textured floor's checkerboard: 32×32 texels, squares of 8, light
/// grey and blue; texel `(i, j)`'s linear colour.
pub(super) fn checker(i: u32, j: u32) -> [f32; 3] {
    let light = (i / 8 + j / 8).is_multiple_of(2);
    let c = if light {
        [230, 230, 230]
    } else {
        [40, 70, 160]
    };
    Lin::from_srgb(Rgb(c)).to_f32().map(|v| v / 65535.0)
}

/// The textured floor's extent in x and z, and its texture coordinates
/// there (8 repeats across, 40 deep: squares half a unit on a side).
pub(super) const FLOOR_X: f64 = 8.0;
pub(super) const FLOOR_Z: [f64; 2] = [-1.0, -81.0];
pub(super) fn floor_uv(x: f64, z: f64) -> [f64; 2] {
    [(x + FLOOR_X) / 2.0, (FLOOR_Z[0] - z) / 2.0]
}

/// A checkerboard floor at y = −1 from 1 to 81 units in front of the eye,
/// seen from the origin with the horizon in view: near the eye a texel
/// covers several samples, far off a sample covers many texels.
pub fn textured_floor() -> Scene {
    use rastty::scene::{Geometry, MaterialRun, Mesh};
    use rastty::texture::{Sampler, Texture};
    use std::sync::Arc;
    let corners = [
        (-FLOOR_X, FLOOR_Z[0]),
        (FLOOR_X, FLOOR_Z[0]),
        (FLOOR_X, FLOOR_Z[1]),
        (-FLOOR_X, FLOOR_Z[1]),
    ];
    let positions = corners
        .iter()
        .map(|&(x, z)| Vec3::new(x as f32, -1.0, z as f32))
        .collect();
    let mut g = Geometry::new("textured floor", positions, vec![[0, 1, 2], [0, 2, 3]]);
    g.uvs = Some(
        corners
            .iter()
            .map(|&(x, z)| glam::Vec2::from(floor_uv(x, z).map(|t| t as f32)))
            .collect(),
    );
    let texels = (0..32 * 32).map(|k| checker(k % 32, k / 32)).collect();
    g.textures = vec![Arc::new(Texture::from_linear(
        "checkerboard",
        32,
        32,
        texels,
        Sampler::default(),
    ))];
    g.materials = vec![MaterialRun {
        first: 0,
        color: None,
        texture: Some(0),
        finish: Default::default(),
    }];
    Scene {
        camera: Camera {
            shift: rastty::glam::Vec2::ZERO,
            projection: Projection::Perspective {
                fov_y: 60.0,
                near: 0.5,
                far: 200.0,
            },
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, -0.3, -1.0),
            up: Vec3::Y,
            fit: None,
        },
        meshes: vec![Mesh::of(Arc::new(g), Rgb::WHITE)],
        ..Scene::default()
    }
}

/// The textured floor drawn with `filter` on a 64×32 grid, each sample
/// against the mean of 16×16 rays cast through its square in f64, each
/// reading the texel it hits: the largest and mean colour error (0–255,
/// linear light) over the samples whose square lies wholly on the floor.
pub fn filter_error(filter: FilterMode) -> (f64, f64) {
    const SUB: u32 = 16;
    let scene = textured_floor();
    let opts = RenderOptions {
        cols: 64,
        rows: 32,
        glyphs: GlyphMode::Block,
        cell_aspect: 1.0,
        filter: Some(filter),
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    renderer.render(&scene, &opts);
    let fb = renderer.framebuffer();
    let grid = fb.grid();
    let inv = scene.camera.view_projection64(opts.aspect()).inverse();
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in 0..grid.height {
        'sample: for x in 0..grid.width {
            let Some(c) = fb.get(x, y) else { continue };
            let mut want = [0.0f64; 3];
            for k in 0..SUB * SUB {
                let ndc = |v: f64, n: u32| v / n as f64 * 2.0 - 1.0;
                let sx = x as f64 + ((k % SUB) as f64 + 0.5) / SUB as f64;
                let sy = y as f64 + ((k / SUB) as f64 + 0.5) / SUB as f64;
                let (nx, ny) = (ndc(sx, grid.width), ndc(sy, grid.height));
                let p0 = inv.project_point3(glam::DVec3::new(nx, ny, -1.0));
                let p1 = inv.project_point3(glam::DVec3::new(nx, ny, 1.0));
                let t = (-1.0 - p0.y) / (p1.y - p0.y);
                let hit = p0 + (p1 - p0) * t;
                let inside = (0.0..=1.0).contains(&t)
                    && hit.x.abs() <= FLOOR_X
                    && (FLOOR_Z[1]..=FLOOR_Z[0]).contains(&hit.z);
                if !inside {
                    continue 'sample;
                }
                let [u, v] = floor_uv(hit.x, hit.z);
                let texel = |t: f64| ((t.rem_euclid(1.0) * 32.0) as u32).min(31);
                let c = checker(texel(u), texel(v));
                for ch in 0..3 {
                    want[ch] += c[ch] as f64 / (SUB * SUB) as f64;
                }
            }
            let got = c.to_f32().map(|v| v as f64 / 257.0);
            let e = (0..3)
                .map(|k| (got[k] - want[k] * 255.0).abs())
                .fold(0.0, f64::max);
            max = max.max(e);
            sum += e;
            n += 1;
        }
    }
    (max, sum / n.max(1) as f64)
}

/// The roughness of the white metal sphere the highlight and environment
/// rows measure.
const SPHERE_ROUGHNESS: f32 = 0.5;

/// A white metal sphere of [`SPHERE_ROUGHNESS`] seen through a parallel
/// view, lit by `light` and `environment` (at 81×81 samples, square), drawn
/// with `highlights`; then, for every `step`-th sample across and down well
/// inside the disc, `want(normal)` (0–255, linear) against the drawn
/// colour: the largest and mean error.
fn sphere_error(
    light: rastty::scene::Light,
    environment: rastty::scene::environment::Environment,
    highlights: Highlights,
    step: usize,
    want: impl Fn(glam::DVec3) -> f64,
) -> (f64, f64) {
    use rastty::scene::{Finish, MaterialRun, Mesh, Shape, Specular};
    let mut sphere = (*Shape::Sphere.geometry()).clone();
    sphere.materials = vec![MaterialRun {
        first: 0,
        color: None,
        texture: None,
        finish: Finish {
            specular: Specular::metallic_roughness(1.0, SPHERE_ROUGHNESS),
            ..Finish::default()
        },
    }];
    let scene = Scene::builder()
        .camera(Camera {
            shift: rastty::glam::Vec2::ZERO,
            projection: Projection::Orthographic {
                height: 2.4,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fit: None,
        })
        .mesh(Mesh::of(std::sync::Arc::new(sphere), Rgb::WHITE))
        .light(light)
        .build()
        .expect("the sphere's scene");
    let scene = Scene {
        environment,
        ..scene
    };
    let opts = RenderOptions {
        cols: 81,
        rows: 81,
        glyphs: GlyphMode::Block,
        cell_aspect: 1.0,
        highlights,
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    renderer.render(&scene, &opts);
    let fb = renderer.framebuffer();
    let grid = fb.grid();
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in (0..grid.height).step_by(step) {
        for x in (0..grid.width).step_by(step) {
            let Some(c) = fb.get(x, y) else { continue };
            // The sample's centre on the view plane, in the sphere's units
            // (y up: the grid's rows count up from the bottom).
            let px = ((x as f64 + 0.5) / grid.width as f64 * 2.0 - 1.0) * 1.2;
            let py = ((y as f64 + 0.5) / grid.height as f64 * 2.0 - 1.0) * 1.2;
            let r2 = px * px + py * py;
            if r2 > 0.9 {
                continue;
            }
            let normal = glam::DVec3::new(px, py, (1.0 - r2).sqrt());
            let got = f64::from(c.to_f32()[0]) / 257.0;
            let e = (got - want(normal).min(255.0)).abs();
            max = max.max(e);
            sum += e;
            n += 1;
        }
    }
    (max, sum / f64::from(n.max(1)))
}

/// A white metal sphere (roughness 0.5) seen through a
/// parallel view and lit from the upper left: every drawn sample's colour
/// (its highlight alone: a metal has no diffuse light, and no environment
/// is reflected) against the same lobe evaluated in f64 at the true
/// sphere's normal behind it. Largest and mean error, 0–255 in linear
/// light, over samples well inside the disc.
pub fn highlight_error(highlights: Highlights) -> (f64, f64) {
    let light = Rgb::new(63, 63, 63);
    let direction = Vec3::new(0.5, -0.4, -1.0);
    let strength = f64::from(Lin::from_srgb(light).to_f32()[0]) / 65535.0;
    let l = -direction.as_dvec3().normalize();
    let a = f64::from(SPHERE_ROUGHNESS * SPHERE_ROUGHNESS);
    let light = rastty::scene::Light {
        direction,
        color: light,
        ambient: 0.0,
        ..rastty::scene::Light::default()
    };
    let none = rastty::scene::environment::Environment::None;
    sphere_error(light, none, highlights, 1, |normal| {
        255.0 * strength * rastty::specular_reference(normal, l, glam::DVec3::Z, 1.0, a * a)
    })
}

/// The white metal sphere lit by `environment` alone (a black light, so
/// that highlights are drawn and add nothing): the largest and mean colour
/// error (0–255, linear) of its samples against the f64 integral of the
/// studio through the renderer's own lobe at the true sphere's normal,
/// every third sample across and down.
pub fn environment_error(environment: rastty::scene::environment::Environment) -> (f64, f64) {
    let a = f64::from(SPHERE_ROUGHNESS * SPHERE_ROUGHNESS);
    let black = rastty::scene::Light {
        color: Rgb::BLACK,
        ambient: 0.0,
        ..rastty::scene::Light::default()
    };
    sphere_error(black, environment, Highlights::Sample, 3, |normal| {
        let studio = &rastty::scene::environment::studio_radiance;
        255.0 * rastty::reflection_reference(studio, normal, glam::DVec3::Z, 1.0, a * a, 96)
    })
}

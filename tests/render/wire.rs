//! Wireframes, end to end: edges drawn once however many faces share
//! them, lines of one sample through the exact rasterizer, edges behind a
//! face hidden, and the planned frame against the full pipeline's.

use std::sync::Arc;

use glam::Vec3;
use rastty::color::{Lin, Rgb};
use rastty::scene::{Camera, Geometry, Mesh, Projection, Scene};
use rastty::{GlyphMode, Pipeline, RenderOptions, Renderer, Threads, Wire};

/// A square from sample centre (10.5, 10.5) to (30.5, 30.5) of a 40×40
/// grid, as two triangles sharing the diagonal from corner to corner, in
/// normalised device coordinates (no projection: x = (ndc + 1) · 20).
fn square() -> Scene {
    let (lo, hi) = (10.5 / 20.0 - 1.0, 30.5 / 20.0 - 1.0);
    let g = Geometry::new(
        "square",
        vec![
            Vec3::new(lo, lo, 0.0),
            Vec3::new(hi, lo, 0.0),
            Vec3::new(hi, hi, 0.0),
            Vec3::new(lo, hi, 0.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    Scene::builder()
        .camera(Camera {
            projection: Projection::None,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(g), Rgb::WHITE))
        .build()
        .unwrap()
}

/// 40×40 samples: 40 columns of 20 half-block cells.
fn opts(wire: Wire) -> RenderOptions {
    RenderOptions {
        cols: 40,
        rows: 20,
        glyphs: GlyphMode::Half,
        wire,
        ..RenderOptions::default()
    }
}

#[test]
fn two_triangles_sharing_an_edge_draw_it_once() {
    let mut r = Renderer::new();
    r.render(&square(), &opts(Wire::Lines));
    let s = *r.stats();
    // Four sides and the diagonal: five edges, not six.
    assert_eq!(s.edges, 5);
    // Each side covers the 21 sample centres from end to end (a line is
    // one sample wide, centred on them); the diagonal those with x = y,
    // 21 again: 105 samples covered. Drawn twice, the diagonal would make
    // it 126.
    assert_eq!(s.raster.samples_covered, 105);
    // The square's outline, 80 samples, and the diagonal's 19 inside it.
    let lit = r.framebuffer().samples().iter().flatten().count();
    assert_eq!(lit, 99);
    let fb = r.framebuffer();
    for k in 10..=30 {
        assert!(fb.get(k, 10).is_some() && fb.get(k, 30).is_some());
        assert!(fb.get(10, k).is_some() && fb.get(30, k).is_some());
        assert!(fb.get(k, k).is_some(), "the diagonal at {k}");
    }
    // Nothing just off a line.
    assert!(fb.get(9, 20).is_none() && fb.get(20, 11).is_none() && fb.get(12, 11).is_none());
}

#[test]
fn lines_alone_draw_no_face_and_solid_draws_no_line() {
    let mut r = Renderer::new();
    r.render(&square(), &opts(Wire::Solid));
    assert_eq!(r.stats().edges, 0);
    let solid = r.framebuffer().samples().iter().flatten().count();
    // The faces: the centres from 10.5 to 30.5, less the top and right
    // edges' (the top-left rule): 20 × 20.
    assert_eq!(solid, 400);
    r.render(&square(), &opts(Wire::Lines));
    // The middle of the square is empty off the diagonal.
    assert!(r.framebuffer().get(25, 15).is_none());
    assert_eq!(r.stats().raster.triangles_drawn, 10, "two a line, no face");
}

/// A square of side `size` facing the eye at depth `z`.
fn quad(size: f32, z: f32) -> Geometry {
    let h = size / 2.0;
    Geometry::new(
        "quad",
        vec![
            Vec3::new(-h, -h, z),
            Vec3::new(h, -h, z),
            Vec3::new(h, h, z),
            Vec3::new(-h, h, z),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// `quads` seen through a perspective camera 5 away.
fn quads(quads: Vec<Geometry>) -> Scene {
    let mut b = Scene::builder().camera(Camera {
        eye: Vec3::new(0.0, 0.0, 5.0),
        ..Camera::default()
    });
    for (g, c) in quads
        .into_iter()
        .zip([Rgb::new(200, 40, 40), Rgb::new(40, 40, 200)])
    {
        b = b.mesh(Mesh::of(Arc::new(g), c));
    }
    b.build().unwrap()
}

fn frame(scene: &Scene, opts: &RenderOptions) -> Vec<Option<Lin>> {
    let mut r = Renderer::new();
    r.render(scene, opts);
    r.framebuffer().samples().to_vec()
}

#[test]
fn edges_behind_a_face_are_hidden_and_its_own_are_not() {
    // A small square a unit behind a large one, inside its outline.
    let both = quads(vec![quad(2.0, 0.0), quad(1.0, -1.0)]);
    let front = quads(vec![quad(2.0, 0.0)]);
    let o = RenderOptions {
        cols: 60,
        rows: 30,
        ..opts(Wire::Edges)
    };
    // With faces, the one behind (edges and all) does not show.
    assert_eq!(frame(&both, &o), frame(&front, &o));
    // The front square's own edges do: black samples on its outline.
    let black = Some(Lin::from_srgb(Rgb::BLACK));
    let edged = frame(&front, &o);
    assert!(edged.iter().filter(|s| **s == black).count() > 100);
    // As lines alone, every edge shows: the square behind too.
    let lines = RenderOptions {
        wire: Wire::Lines,
        ..o
    };
    assert_ne!(frame(&both, &lines), frame(&front, &lines));
}

#[test]
fn wireframes_are_the_same_planned_or_full_and_in_bands() {
    let scene = quads(vec![quad(2.0, 0.0), quad(1.0, -1.0)]);
    for wire in [Wire::Lines, Wire::Edges] {
        let o = RenderOptions {
            cols: 60,
            rows: 30,
            turn: Vec3::new(20.0, 35.0, 0.0),
            ..opts(wire)
        };
        let planned = frame(&scene, &o);
        let full = RenderOptions {
            pipeline: Pipeline::Full,
            ..o
        };
        assert_eq!(planned, frame(&scene, &full), "{wire:?}");
        let banded = RenderOptions {
            threads: Threads::Exactly(3),
            ..o
        };
        assert_eq!(planned, frame(&scene, &banded), "{wire:?} in bands");
    }
}

//! What posing costs: a skinned tube (200 rings of 64 vertices, 12,800
//! vertices, four joints, each vertex weighted between two) rendered at
//! 200×60 half blocks, frame after frame, as `scripts/figures.sh` counts
//! it under callgrind:
//!
//! ```text
//! cargo run --release -p rastty-measure --bin pose_cost -- MODE FRAMES
//! ```
//!
//! MODE is `static` (the same tube without a rig), `held` (its clip held
//! at one time: posed once, then drawn as it stands) or `playing` (the
//! clip at frame / 30 s: posed every frame).

use std::f32::consts::TAU;
use std::sync::Arc;

use glam::{Mat4, Quat, Vec3};
use rastty::scene::anim::{
    Binding, Channel, Clip, Interpolation, Node, Part, Property, Rig, Sampler, Skin, Trs,
};
use rastty::scene::{Geometry, Mesh, Scene};
use rastty::{RenderOptions, Renderer, color::Rgb};

const RINGS: usize = 200;
const AROUND: usize = 64;
const JOINTS: usize = 4;
const LENGTH: f32 = 4.0;

/// The tube's rest positions and faces, along y from 0 to `LENGTH`.
fn tube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut p = Vec::with_capacity(RINGS * AROUND);
    for r in 0..RINGS {
        let y = LENGTH * r as f32 / (RINGS - 1) as f32;
        for a in 0..AROUND {
            let t = TAU * a as f32 / AROUND as f32;
            p.push(Vec3::new(0.3 * t.cos(), y, 0.3 * t.sin()));
        }
    }
    let mut f = Vec::new();
    for r in 0..RINGS - 1 {
        for a in 0..AROUND {
            let i = |r: usize, a: usize| (r * AROUND + a % AROUND) as u32;
            f.push([i(r, a), i(r + 1, a), i(r + 1, a + 1)]);
            f.push([i(r, a), i(r + 1, a + 1), i(r, a + 1)]);
        }
    }
    (p, f)
}

/// The tube skinned by a chain of joints along it, each bending 20° about
/// z and back over 2 s.
fn rig(positions: &[Vec3], normals: &[Vec3]) -> Rig {
    let spacing = LENGTH / JOINTS as f32;
    let nodes = (0..JOINTS)
        .map(|j| Node {
            parent: j.checked_sub(1).map(|p| p as u32),
            rest: Ok(Trs {
                translation: Vec3::new(0.0, if j == 0 { 0.0 } else { spacing }, 0.0),
                rotation: Quat::IDENTITY,
                scale: Vec3::ONE,
            }),
            weights: Vec::new(),
            source: None,
        })
        .collect();
    let inverse_bind = (0..JOINTS)
        .map(|j| Mat4::from_translation(Vec3::new(0.0, -spacing * j as f32, 0.0)))
        .collect();
    let mut starts = vec![0];
    let mut influences = Vec::new();
    for p in positions {
        // Between the two joints nearest along the tube.
        let at = (p.y / spacing).clamp(0.0, (JOINTS - 1) as f32);
        let j = (at.floor() as usize).min(JOINTS - 2);
        let w = at - j as f32;
        influences.push((j as u16, 1.0 - w));
        influences.push((j as u16 + 1, w));
        starts.push(influences.len() as u32);
    }
    let bend = Quat::from_rotation_z(20f32.to_radians());
    let channels = (0..JOINTS as u32)
        .map(|node| Channel {
            node,
            property: Property::Rotation,
            sampler: Sampler::new(
                vec![0.0, 1.0, 2.0],
                [Quat::IDENTITY, bend, Quat::IDENTITY]
                    .iter()
                    .flat_map(|q| q.to_array())
                    .collect(),
                4,
                Interpolation::Linear,
            )
            .expect("keyframes"),
        })
        .collect();
    let mut rig = Rig {
        nodes,
        skins: vec![Skin {
            joints: (0..JOINTS as u32).collect(),
            inverse_bind,
        }],
        clips: vec![Clip {
            name: "bend".into(),
            channels,
            length: 2.0,
            moves: Vec::new(),
        }],
        parts: vec![Part {
            first: 0,
            positions: positions.to_vec(),
            normals: normals.to_vec(),
            binding: Binding::Skin {
                skin: 0,
                starts,
                influences,
                node: 0,
            },
            morph: None,
        }],
        fitted: Vec::new(),
    };
    rig.settle();
    rig
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mode = args.next().unwrap_or_else(|| "playing".into());
    let frames: u64 = args.next().and_then(|n| n.parse().ok()).unwrap_or(40);
    let (positions, faces) = tube();
    let mut geometry = Geometry::new("tube", positions, faces);
    if mode != "static" {
        let rig = rig(&geometry.positions, &geometry.normals);
        // The rest pose, as the loader writes it: by the posing code.
        let (mut p, mut n) = (geometry.positions.clone(), geometry.normals.clone());
        rig.pose_into(None, &mut Default::default(), &mut p, &mut n);
        (geometry.positions, geometry.normals) = (p, n);
        geometry.analyze();
        geometry.rig = Some(Arc::new(rig));
    }
    let mut scene = Scene::of_mesh(Mesh::of(Arc::new(geometry), Rgb::new(200, 160, 120)));
    let opts = RenderOptions {
        cols: 200,
        rows: 60,
        ..RenderOptions::default()
    };
    let mut renderer = Renderer::new();
    let mut covered = 0;
    for k in 0..frames {
        match mode.as_str() {
            "playing" => scene.set_pose(0, k as f64 / 30.0),
            "held" => scene.set_pose(0, 0.5),
            _ => {}
        }
        renderer.render(&scene, &opts);
        covered += renderer.stats().raster.samples_covered;
    }
    println!("{mode}: {frames} frames, {covered} samples covered");
}

//! `rastty render --explain`: the renderer's last frame told as a report,
//! the plan's decisions beside the work each stage did. Kept next to the
//! renderer, whose statistics it reads; the planner only decides.

use crate::plan::Effect;
use std::fmt::Write as _;
use std::time::Duration;

use super::Renderer;
use crate::options::RenderOptions;
use crate::scene::Scene;

impl Renderer {
    /// The report `rastty render --explain` prints: the frame, each stage run
    /// or skipped and why, the work each did (from the frame's statistics,
    /// where a skipped stage shows zero) and where the time went.
    #[must_use]
    pub fn explain(
        &self,
        scene: &Scene,
        opts: &RenderOptions,
        encode: Duration,
        bytes: usize,
    ) -> String {
        let Some(plan) = self.plan() else {
            return "no frame rendered\n".into();
        };
        let s = self.stats();
        let t = self.times();
        let grid = opts.grid();
        let (w, h) = opts.cell_samples();
        let ms = |d: Duration| format!("{:.3} ms", d.as_secs_f64() * 1e3);
        let mut out = String::new();
        let _ = writeln!(
            out,
            "frame: {}×{} cells, {:?} glyphs ({} samples a cell, {}×{} samples), {} triangles, {} pipeline",
            opts.cols,
            opts.rows,
            opts.glyphs,
            w * h,
            grid.width,
            grid.height,
            scene.triangle_count(),
            if plan.full { "full" } else { "planned" },
        );
        // What moves: each moving model's clips, skins and morph targets,
        // and the pose drawn.
        for (i, m) in scene.meshes.iter().enumerate() {
            let Some(rig) = &m.rig else { continue };
            let targets = rig
                .parts
                .iter()
                .filter_map(|p| {
                    let m = p.morph.as_ref()?;
                    Some(m.positions.len() / p.positions.len().max(1))
                })
                .max()
                .unwrap_or(0);
            let joints: usize = rig.skins.iter().map(|s| s.joints.len()).sum();
            let _ = writeln!(
                out,
                "mesh {i} moves: {} nodes, {} skins ({joints} joints), {targets} morph targets; {}",
                rig.nodes.len(),
                rig.skins.len(),
                match m.pose {
                    Some(p) => match rig.clips.get(p.clip) {
                        Some(c) => format!(
                            "clip {} at {:.3} s ({:.3} s into it)",
                            p.clip,
                            p.time,
                            c.local(p.time)
                        ),
                        None => format!("clip {} (none such): at rest", p.clip),
                    },
                    None => "at rest".into(),
                }
            );
            for (k, c) in rig.clips.iter().enumerate() {
                let _ = writeln!(
                    out,
                    "  clip {k} {}: {:.3} s, {} channels ({}){}",
                    if c.name.is_empty() {
                        "(unnamed)".to_string()
                    } else {
                        crate::text::name(&c.name, 40)
                    },
                    c.length,
                    c.channels.len(),
                    channels(rig, c),
                    if c.moves.contains(&true) {
                        ""
                    } else {
                        "; moves no vertex"
                    }
                );
            }
        }
        // Each stage runs inside a timed phase (the last line): the vertex
        // phase holds the clip tests and per-vertex lighting, the triangle
        // phase the rest.
        for (e, d) in plan.decisions() {
            let work = e.work(s, scene, opts, plan);
            let _ = writeln!(out, "{:<14} {d}\n{:<20}{work}", e.name(), "");
        }
        effects(&mut out, scene, plan);
        deferrals(&mut out, scene, opts, plan);
        let r = &s.raster;
        let _ = writeln!(
            out,
            "raster: {} triangles set up, {} found empty, {} culled, {} degenerate, {} not finite; {} samples tested, {} covered",
            r.triangles_drawn,
            r.found_empty,
            r.culled,
            r.dropped_degenerate,
            r.dropped_non_finite,
            r.samples_tested,
            r.samples_covered
        );
        let _ = writeln!(
            out,
            "bands          {}\n{:<20}{}",
            plan.bands,
            "",
            if plan.bands.count > 1 {
                "each a thread; vertices transformed once, each triangle set up by every band it reaches"
            } else {
                "one thread draws every row"
            }
        );
        let _ = writeln!(
            out,
            "time: plan {} · vertices {} · triangles {} · blit {} · encode {} ({} bytes)",
            ms(t.plan),
            ms(t.vertices),
            ms(t.triangles),
            ms(t.blit),
            ms(encode),
            bytes
        );
        out
    }
}

/// The most runs of one mesh `--explain` lists one by one.
const RUNS_LISTED: usize = 8;

/// Which meshes' faces get which of the plan's per-material effects, run
/// by run, and what in their material calls for it; a mesh whose faces
/// get none is not listed.
fn effects(out: &mut String, scene: &Scene, plan: &crate::plan::Plan) {
    for (i, m) in scene.meshes.iter().enumerate() {
        let runs: Vec<String> = m
            .runs(crate::color::Lin::from_srgb(m.color))
            .filter_map(|run| {
                let f = &run.finish;
                let mut e = Vec::new();
                if run.texture.is_some() && plan[Effect::Texturing].run {
                    e.push("texture (its base colour's)".to_string());
                }
                if let Some(maps) = plan.maps_of(f).filter(|_| m.uvs.is_some()) {
                    let which: Vec<&str> = [
                        (maps.normal.is_some(), "normal"),
                        (maps.metallic_roughness.is_some(), "metallic-roughness"),
                        (maps.occlusion.is_some(), "occlusion"),
                        (maps.emissive.is_some(), "emissive"),
                        (maps.specular_glossiness.is_some(), "specular-glossiness"),
                    ]
                    .iter()
                    .filter_map(|&(has, name)| has.then_some(name))
                    .collect();
                    e.push(format!("maps ({}): shaded per sample", which.join(", ")));
                } else if f.specular.is_some() && !f.unlit && plan.shines(true) {
                    e.push("highlight (its metallic-roughness or Ks)".into());
                }
                let layers = plan.layers_of(f);
                if let Some(c) = layers.clearcoat {
                    e.push(format!(
                        "clear coat ({}, roughness {})",
                        c.factor, c.roughness
                    ));
                }
                if let Some(s) = layers.sheen {
                    e.push(format!("sheen (roughness {})", s.roughness));
                }
                if plan[Effect::Glow].run && f.emissive != crate::color::Lin::BLACK {
                    e.push("glow (its emissive colour)".into());
                }
                if plan.sees_through(&f.alpha) {
                    match f.alpha.mode {
                        crate::scene::AlphaMode::Mask { cutoff } => {
                            e.push(format!("mask (cut at alpha {cutoff})"));
                        }
                        crate::scene::AlphaMode::Blend => {
                            e.push("blend (drawn last, back to front)".into());
                        }
                        crate::scene::AlphaMode::Opaque => {}
                    }
                }
                if f.unlit {
                    e.push("unlit (drawn in its colour)".into());
                }
                (!e.is_empty()).then(|| {
                    format!(
                        "faces {}..{}: {}",
                        run.faces.start,
                        run.faces.end,
                        e.join(", ")
                    )
                })
            })
            .collect();
        if runs.is_empty() {
            continue;
        }
        let _ = writeln!(
            out,
            "mesh {i} ({}), its materials' effects:",
            crate::text::name(&m.geometry.name, 40)
        );
        for r in runs.iter().take(RUNS_LISTED) {
            let _ = writeln!(out, "  {r}");
        }
        if runs.len() > RUNS_LISTED {
            let _ = writeln!(out, "  … and {} more runs", runs.len() - RUNS_LISTED);
        }
    }
}

/// Each mesh's [`crate::Plan::deferral`]: whether its vertices' depth and
/// light are found again at set-up, why, and how many vertices it has a
/// sample (the first [`RUNS_LISTED`] meshes).
fn deferrals(out: &mut String, scene: &Scene, opts: &RenderOptions, plan: &crate::plan::Plan) {
    let grid = opts.grid();
    let samples = (grid.width as f64 * grid.height as f64).max(1.0);
    for (i, m) in scene.meshes.iter().enumerate().take(RUNS_LISTED) {
        let cull = plan.cull(i);
        let d = plan.deferral(i, cull);
        let _ = writeln!(
            out,
            "{:<14} {d}\n{:<20}mesh {i}: {} vertices, {:.1} a sample; {} bytes a vertex kept",
            "lazy vertices",
            "",
            m.positions.len(),
            m.positions.len() as f64 / samples,
            super::vertex::Core::BYTES
                + match plan.vertex_extras(i, cull) {
                    crate::plan::Extras::Found => 0,
                    crate::plan::Extras::Deep => size_of::<super::vertex::Deep>(),
                    crate::plan::Extras::All => size_of::<super::vertex::More>(),
                },
        );
    }
    if scene.meshes.len() > RUNS_LISTED {
        let _ = writeln!(
            out,
            "  … and {} more meshes",
            scene.meshes.len() - RUNS_LISTED
        );
    }
}

/// A clip's channels for `--explain`: each one where there are a few, a
/// summary (nodes, paths, keys, interpolations) where a skeleton has many,
/// so that a 50-joint figure's clip stays one readable line.
fn channels(rig: &crate::scene::anim::Rig, c: &crate::scene::anim::Clip) -> String {
    const EACH: usize = 6;
    if c.channels.len() <= EACH {
        return c
            .channels
            .iter()
            .map(|ch| {
                format!(
                    "node {} {} {} keys {}",
                    file_node(rig, ch.node),
                    ch.property.name(),
                    ch.sampler.keys(),
                    ch.sampler.interpolation().name()
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
    }
    let mut nodes: Vec<u32> = c.channels.iter().map(|ch| ch.node).collect();
    nodes.sort_unstable();
    nodes.dedup();
    // Counted by name in first-seen order: a handful of paths and modes.
    let mut paths: Vec<(&str, usize)> = Vec::new();
    let mut modes: Vec<(&str, usize)> = Vec::new();
    for ch in &c.channels {
        for (list, name) in [
            (&mut paths, ch.property.name()),
            (&mut modes, ch.sampler.interpolation().name()),
        ] {
            match list.iter_mut().find(|(n, _)| *n == name) {
                Some((_, k)) => *k += 1,
                None => list.push((name, 1)),
            }
        }
    }
    let join = |l: &[(&str, usize)]| {
        l.iter()
            .map(|(n, k)| format!("{k} {n}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let keys = c.channels.iter().map(|ch| ch.sampler.keys());
    format!(
        "on {} node{}: {}; {} to {} keys; {}",
        nodes.len(),
        if nodes.len() == 1 { "" } else { "s" },
        join(&paths),
        keys.clone().min().unwrap_or(0),
        keys.max().unwrap_or(0),
        join(&modes)
    )
}

/// A rig's node as the file numbers it (the rig's own index where it was
/// built in code).
fn file_node(rig: &crate::scene::anim::Rig, node: u32) -> u32 {
    rig.nodes
        .get(node as usize)
        .and_then(|n| n.source)
        .unwrap_or(node)
}

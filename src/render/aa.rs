//! Anti-aliasing: the frame drawn in several passes, one per sub-sample
//! position (`4x`, `16x`: the geometry shifted so that sample centres land
//! on each), or once with exact area coverage (`exact`), into per-sample
//! sums of colour and weight; the sums then become samples, the coverage
//! blending the mean colour with the background. Costs a pass per
//! sub-sample, or the exact area of every sample a triangle touches;
//! `rastty bench` measures what each buys.

use std::time::Duration;

use glam::{Mat4, Vec3};

use super::{Renderer, Stage};
use crate::color::{Lin, Rgb};
use crate::options::{Aa, RenderOptions};
use crate::plan::Effect;
use crate::scene::Scene;
use crate::transform;

impl Renderer {
    /// Draws the frame with `opts.aa` (not [`Aa::None`]) into the
    /// accumulator and resolves it into the framebuffer.
    pub(super) fn antialiased(
        &mut self,
        scene: &Scene,
        opts: &RenderOptions,
        stage: &Stage<'_>,
        (vp, turn): (Mat4, Mat4),
        lap: &mut impl FnMut() -> Duration,
    ) {
        let grid = opts.grid();
        let depth = stage.plan[Effect::Depth].run;
        self.acc.clear();
        self.acc.resize(grid.len(), [0.0; 4]);
        if matches!(opts.aa, Aa::Exact) {
            self.fb.reset(grid, depth);
            let exact = Stage {
                exact: true,
                ..*stage
            };
            self.geometry(scene, opts, &exact, vp, turn, lap);
            self.resolve(1.0, scene.background);
            return;
        }
        // One pass per sub-sample position, the geometry shifted so that
        // sample centres land on it; the passes are averaged.
        let offsets = opts.aa.offsets();
        for &(ox, oy) in offsets {
            self.fb.reset(grid, depth);
            let shifted = Stage {
                viewport: transform::Viewport::new(grid.width as f32, grid.height as f32)
                    .shifted(0.5 - ox, 0.5 - oy),
                ..*stage
            };
            self.geometry(scene, opts, &shifted, vp, turn, lap);
            for (a, s) in self.acc.iter_mut().zip(self.fb.samples()) {
                if let Some(c) = s {
                    let [r, g, b] = c.to_f32();
                    *a = [a[0] + r, a[1] + g, a[2] + b, a[3] + 1.0];
                }
            }
        }
        self.resolve(offsets.len() as f32, scene.background);
    }

    /// Turns the accumulated colour sums and weights into samples: weight
    /// over `total` is the coverage, which blends the mean colour with the
    /// background (where there is none, a sample at least half covered
    /// shows its colour, the rest the terminal's).
    fn resolve(&mut self, total: f32, background: Option<Rgb>) {
        let grid = self.fb.grid();
        let bg = background.map(|c| Vec3::from(Lin::from_srgb(c).to_f32()));
        for (i, a) in self.acc.iter().enumerate() {
            let (x, y) = (i as u32 % grid.width, i as u32 / grid.width);
            let weight = a[3];
            if weight <= 0.0 {
                continue;
            }
            let coverage = (weight / total).min(1.0);
            let mean = Vec3::new(a[0], a[1], a[2]) / weight;
            let c = match bg {
                Some(bg) => mean * coverage + bg * (1.0 - coverage),
                None if coverage >= 0.5 => mean,
                None => continue,
            };
            self.fb.set(x, y, Lin::from_f32(c.to_array()));
        }
    }

    /// How much of each sample's square the last frame covered, in [0, 1],
    /// row by row from the bottom, before it became a colour: 0 or 1
    /// without anti-aliasing, the share of sub-samples hit with `4x` and
    /// `16x`, the summed area (capped at 1) with `exact`. What `rastty
    /// bench` measures the coverage knob by.
    pub fn coverage(&self, out: &mut Vec<f32>) {
        out.clear();
        match self.aa {
            Aa::None => out.extend(
                self.fb
                    .samples()
                    .iter()
                    .map(|s| if s.is_some() { 1.0 } else { 0.0 }),
            ),
            aa => {
                let passes = aa.passes() as f32;
                out.extend(self.acc.iter().map(|a| (a[3] / passes).min(1.0)));
            }
        }
    }
}

//! Cutting a model file's polygons into triangles.
//!
//! * **Triangles** pass as they are.
//! * **Quads**, most faces of most models, are cut along the diagonal whose
//!   two triangles face the same way (either, for a convex quad; the one
//!   through the reflex corner, for a dart): a few cross products, no
//!   projection.
//!   A quad that is not flat and whose triangles face apart by both
//!   diagonals is folded (only its projection crosses itself) and is cut
//!   along the diagonal from its first corner, as common loaders do, so a
//!   closed surface stays closed: see [`quad`].
//! * **Everything else** (larger polygons, and a flat quad that crosses itself)
//!   is projected onto the plane that fits it best (Newell's normal) and
//!   triangulated with its edges as constraints by the `spade` crate
//!   (a constrained Delaunay triangulation, bulk-loaded in `O(n log n)`,
//!   exact predicates): repeated and collinear corners are no trouble, and
//!   a face of 100,000 corners is loaded and drawn in well under a second.
//!   Not ear clipping (the `earcut` crate): it turns quadratic on the
//!   f32-rounded outlines real files have (a 100,000-corner circle takes
//!   seconds) and cannot fill a polygon that crosses itself.
//! * **Self-intersecting polygons** (a bowtie) are filled by the **even-odd
//!   rule**, the rule of SVG's `fill-rule: evenodd`: a point is inside when
//!   a ray from it crosses the outline an odd number of times. Edges that
//!   cross are split where they cross (a new vertex, interpolated along the
//!   edge), and the triangles are kept by the parity of the outline edges
//!   crossed on the way in from outside. A bowtie's two lobes are drawn and
//!   the gaps beside its crossing are not. (An edge the outline walks twice
//!   counts once.)
//!
//! Every triangle keeps the polygon's facing (its normal points the way the
//! polygon's does).
//!
//! spade can fail on some degenerate outlines (corners far off one plane
//! that project onto nearly the same point: "Failed to locate position.
//! This is a bug in spade."). A file must never make rastty panic, so the
//! triangulation runs under `catch_unwind`, with a panic hook installed
//! once that stays quiet on the thread while it runs (and passes every
//! other panic to the hook that was there); a polygon it fails on is cut
//! as a fan from its first corner, and [`Triangulator::fallbacks`] counts
//! them for the loader's note.

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

use glam::{DVec3, Vec3, Vec3A};
use rustc_hash::FxHashMap;
use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// A corner of a triangle cut from a polygon: one of the polygon's own
/// corners, or a new point on its edge from corner `a` to corner `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Point {
    Corner(u32),
    Between { a: u32, b: u32, t: f32 },
}

/// How far from flat (as the sine of the angle between its two halves'
/// normals) a quad whose halves face apart by either diagonal must be to
/// count as folded rather than a bowtie: 1°. A bowtie written to a file
/// with six decimals is flat to far less; Tux's one such quad is folded by
/// 38°.
const FOLDED_SIN: f64 = 0.017_452_406_437_283_51;

/// Whether normals `n` and `m` are more than 1° from parallel (either
/// way), in f64 so that a tiny quad's squared areas do not underflow.
fn folded(n: DVec3, m: DVec3) -> bool {
    n.cross(m).length_squared() > FOLDED_SIN * FOLDED_SIN * n.length_squared() * m.length_squared()
}

/// Where to cut a quad `p`: `Some(d)` for the diagonal from corner `d`
/// (0 or 1) to corner `d + 2`; `None` for a flat quad that crosses itself
/// (a bowtie, filled by the even-odd rule) or that has no area.
///
/// * A quad whose two triangles face the same way by some diagonal is cut
///   along it (either, for a convex quad; the one through the reflex
///   corner, for a dart).
/// * A quad whose triangles face apart by both diagonals but which is not
///   flat is **folded**, not crossed: out of its plane its edges do not
///   meet, and only the projection onto one plane makes it look like a
///   bowtie. The file means the surface spanned by its four edges, so it
///   is cut along the diagonal from corner 0, as tinyobjloader and tobj
///   cut every quad. Either diagonal keeps its four edges, so a closed
///   surface stays closed; the even-odd cut would add a vertex on two of
///   them and open it.
///
pub fn quad(p: [Vec3; 4]) -> Option<usize> {
    quad_at(&p, [0, 1, 2, 3])
}

/// [`quad`] of the quad whose corners are `positions[v[k]]`, read from
/// where they are (a reader cuts its quads with no copy of the corners).
/// Panics if an index is out of range.
///
/// Out of line: a quad is cut once, at load; inlined into the OBJ reader
/// it saves less there than the frame's face loop loses by how the
/// compiler then lays the program out.
#[inline(never)]
pub fn quad_at(positions: &[Vec3], v: [u32; 4]) -> Option<usize> {
    // In SIMD lanes: the same operations on each coordinate, and the dot
    // products summed in the same order, so the same bits as `Vec3`'s.
    let at = |k: usize| Vec3A::from(positions[v[k] as usize]);
    let p = [at(0), at(1), at(2), at(3)];
    let facing = |a: usize, b: usize, d: usize| (p[b] - p[a]).cross(p[d] - p[a]);
    let (n, m) = (facing(0, 1, 2), facing(0, 2, 3));
    if n.dot(m) > 0.0 {
        Some(0)
    } else if facing(1, 2, 3).dot(facing(1, 3, 0)) > 0.0 {
        Some(1)
    } else if folded(Vec3::from(n).as_dvec3(), Vec3::from(m).as_dvec3()) {
        Some(0)
    } else {
        None
    }
}

/// Reusable buffers for cutting polygons.
#[derive(Debug, Default)]
pub struct Triangulator {
    flat: Vec<[f64; 2]>,
    /// Polygons spade failed on, cut as fans instead.
    pub fallbacks: usize,
    /// Polygons that cross themselves at more than [`MAX_CROSSINGS`]
    /// allows, cut as fans instead.
    pub crossed: usize,
}

/// The most points at which a polygon of `n` corners is cut where its edges
/// cross: `n + 64` (a star of a few points crosses itself at more points
/// than it has corners). Each adds a corner and about two triangles, so a
/// polygon's cut holds at most `2n + 64` corners and `4n + 128` triangles
/// whatever it is: its memory a small multiple of its corners, where a
/// polygon whose every edge crosses every other (a few thousand random
/// corners) would have a crossing for each pair. A polygon that needs more
/// is cut as a fan, and the loader says so.
pub fn max_crossings(n: usize) -> usize {
    n + 64
}

/// The cut went past [`max_crossings`].
struct TooCrossed;

thread_local! {
    /// Whether a panic on this thread is spade's, caught and answered.
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f`, catching a panic without a word from the panic hook.
fn quietly<T>(f: impl FnOnce() -> T) -> Option<T> {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let r = panic::catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(false));
    r.ok()
}

impl Triangulator {
    pub fn new() -> Triangulator {
        Triangulator::default()
    }

    /// Cuts the polygon with corners at `corners` (in order) into
    /// triangles, appended to `out`.
    pub fn triangulate(&mut self, corners: &[Vec3], out: &mut Vec<[Point; 3]>) {
        let c = |i: u32| Point::Corner(i);
        match corners.len() {
            0..=2 => {}
            3 => out.push([c(0), c(1), c(2)]),
            4 => match quad([corners[0], corners[1], corners[2], corners[3]]) {
                Some(d) => {
                    let [a, b, e, f] = [d, d + 1, d + 2, (d + 3) % 4].map(|i| c(i as u32));
                    out.push([a, b, e]);
                    out.push([a, e, f]);
                }
                None => self.general(corners, out),
            },
            _ => self.general(corners, out),
        }
    }

    /// Projects and triangulates with the edges as constraints, keeping
    /// the even-odd inside; a fan where spade fails, or where the polygon
    /// crosses itself too often.
    fn general(&mut self, corners: &[Vec3], out: &mut Vec<[Point; 3]>) {
        let before = out.len();
        let cut = quietly(|| self.cdt(corners, out));
        if !matches!(cut, Some(Ok(()))) {
            out.truncate(before);
            match cut {
                Some(Err(TooCrossed)) => self.crossed += 1,
                _ => self.fallbacks += 1,
            }
            let n = corners.len() as u32;
            out.extend(
                (1..n - 1).map(|i| [Point::Corner(0), Point::Corner(i), Point::Corner(i + 1)]),
            );
        }
    }

    /// The constrained Delaunay triangulation of [`Triangulator::general`].
    fn cdt(&mut self, corners: &[Vec3], out: &mut Vec<[Point; 3]>) -> Result<(), TooCrossed> {
        let n = corners.len();
        let Some(axes) = plane(corners) else {
            return Ok(()); // every corner on one line: no area
        };
        self.flat.clear();
        self.flat.extend(corners.iter().map(|p| {
            let p = p.as_dvec3();
            [p.dot(axes.0), p.dot(axes.1)]
        }));
        // One vertex per distinct point (a repeated corner is one vertex),
        // and for each the first corner there.
        let mut first_at: FxHashMap<[u64; 2], u32> = FxHashMap::default();
        let mut unique: Vec<Point2<f64>> = Vec::with_capacity(n);
        let mut corner_of: Vec<u32> = Vec::with_capacity(n);
        let vertex: Vec<usize> = self
            .flat
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let next = unique.len() as u32;
                let v = *first_at
                    .entry(p.map(|c| (c + 0.0).to_bits()))
                    .or_insert(next);
                if v == next {
                    unique.push(Point2::new(p[0], p[1]));
                    corner_of.push(i as u32);
                }
                v as usize
            })
            .collect();
        if unique.len() < 3 {
            return Ok(());
        }
        let edges: Vec<[usize; 2]> = (0..n)
            .map(|i| [vertex[i], vertex[(i + 1) % n]])
            .filter(|e| e[0] != e[1])
            .collect();
        // Edges that cross others are added one by one after the bulk load,
        // split where they cross.
        let mut crossing = Vec::new();
        let Ok(mut cdt) = ConstrainedDelaunayTriangulation::<Point2<f64>>::try_bulk_load_cdt(
            unique,
            edges,
            |e| crossing.push(e),
        ) else {
            return Ok(()); // non-finite coordinates
        };
        let known = cdt.num_vertices();
        let most = known + max_crossings(n);
        // Vertices made by splits, with the polygon edge they lie on.
        let mut made: FxHashMap<usize, Point> = FxHashMap::default();
        for [a, b] in crossing {
            if cdt.num_vertices() > most {
                return Err(TooCrossed);
            }
            let sub = cdt.add_constraint_and_split(
                FixedVertexHandle::from_index(a),
                FixedVertexHandle::from_index(b),
                |v| v,
            );
            let (ca, cb) = (corner_of[a], corner_of[b]);
            let (pa, pb) = (self.flat[ca as usize], self.flat[cb as usize]);
            let len2 = (pb[0] - pa[0]).powi(2) + (pb[1] - pa[1]).powi(2);
            for e in sub {
                let v = cdt.directed_edge(e).to();
                if v.fix().index() >= known {
                    let q = v.position();
                    let t =
                        ((q.x - pa[0]) * (pb[0] - pa[0]) + (q.y - pa[1]) * (pb[1] - pa[1])) / len2;
                    made.entry(v.fix().index()).or_insert(Point::Between {
                        a: ca,
                        b: cb,
                        t: t.clamp(0.0, 1.0) as f32,
                    });
                }
            }
        }
        if cdt.num_vertices() > most {
            return Err(TooCrossed);
        }
        // Parity from outside: each outline edge crossed flips it.
        let mut parity: FxHashMap<usize, bool> = FxHashMap::default();
        let mut todo: Vec<(
            spade::handles::FixedFaceHandle<spade::handles::InnerTag>,
            bool,
        )> = Vec::new();
        for e in cdt.convex_hull() {
            if let Some(inner) = e.rev().face().as_inner() {
                todo.push((inner.fix(), cdt.is_constraint_edge(e.as_undirected().fix())));
            }
        }
        while let Some((f, odd)) = todo.pop() {
            if parity.insert(f.index(), odd).is_some() {
                continue;
            }
            for e in cdt.face(f).adjacent_edges() {
                if let Some(next) = e.rev().face().as_inner()
                    && !parity.contains_key(&next.fix().index())
                {
                    let flip = cdt.is_constraint_edge(e.as_undirected().fix());
                    todo.push((next.fix(), odd ^ flip));
                }
            }
        }
        for face in cdt.inner_faces() {
            if parity.get(&face.fix().index()) != Some(&true) {
                continue;
            }
            // spade's faces are counter-clockwise, as the projected polygon.
            out.push(face.vertices().map(|v| {
                let i = v.fix().index();
                if i < known {
                    Point::Corner(corner_of[i])
                } else {
                    made.get(&i).copied().unwrap_or(Point::Corner(0))
                }
            }));
        }
        Ok(())
    }
}

/// The loader's note for the polygons `cutter` cut as fans, if any.
pub fn fallback_note(name: &str, cutter: &Triangulator) -> Option<String> {
    let mut what = Vec::new();
    if cutter.fallbacks > 0 {
        what.push(format!(
            "{} polygon(s) too degenerate to triangulate exactly (far off one plane)",
            cutter.fallbacks
        ));
    }
    if cutter.crossed > 0 {
        what.push(format!(
            "{} polygon(s) crossing themselves at more points than they have corners (and 64)",
            cutter.crossed
        ));
    }
    (!what.is_empty()).then(|| {
        format!(
            "{name}: {} were cut as fans from their first corner",
            what.join(", and ")
        )
    })
}

/// Two axes spanning the polygon's plane, oriented so that the projected
/// polygon runs counter-clockwise (positive area); `None` when every corner
/// is on one line.
fn plane(corners: &[Vec3]) -> Option<(DVec3, DVec3)> {
    let n = corners.len();
    // Newell's normal: the polygon's area vector, whatever its shape.
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (corners[i].as_dvec3(), corners[(i + 1) % n].as_dvec3());
        normal += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    if normal.length_squared() == 0.0 || !normal.is_finite() {
        // A bowtie's lobes cancel: take the plane of the widest corner.
        let o = corners[0].as_dvec3();
        normal = corners
            .windows(2)
            .map(|w| (w[0].as_dvec3() - o).cross(w[1].as_dvec3() - o))
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))?;
        if normal.length_squared() == 0.0 || !normal.is_finite() {
            return None;
        }
    }
    let n = normal.normalize();
    let u = n.any_orthonormal_vector();
    Some((u, n.cross(u)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// A quad's cut decided in SIMD lanes is the cut decided one
        /// coordinate at a time (`Vec3`), for quads of every shape and
        /// scale, flat, folded, crossed and degenerate among them.
        #[test]
        fn quad_in_lanes_is_quad_in_scalars(
            c in prop::collection::vec(
                prop_oneof![(-4i32..5).prop_map(|i| i as f32 / 7.0), -1.0f32..1.0],
                12,
            ),
            scale in prop::sample::select(vec![1e-30f32, 1e-3, 0.37, 1.0, 3.0e4, 1e30]),
            flat: bool,
        ) {
            let p: [Vec3; 4] = std::array::from_fn(|k| {
                let z = if flat { 0.0 } else { c[3 * k + 2] };
                Vec3::new(c[3 * k], c[3 * k + 1], z) * scale
            });
            let facing = |a: usize, b: usize, d: usize| (p[b] - p[a]).cross(p[d] - p[a]);
            let (n, m) = (facing(0, 1, 2), facing(0, 2, 3));
            let scalar = if n.dot(m) > 0.0 {
                Some(0)
            } else if facing(1, 2, 3).dot(facing(1, 3, 0)) > 0.0 {
                Some(1)
            } else if folded(n.as_dvec3(), m.as_dvec3()) {
                Some(0)
            } else {
                None
            };
            prop_assert_eq!(quad(p), scalar);
        }
    }

    fn flat(pts: &[(f32, f32)]) -> Vec<Vec3> {
        pts.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect()
    }

    /// The triangles' positions.
    fn resolve(c: &[Vec3], t: &[[Point; 3]]) -> Vec<[Vec3; 3]> {
        t.iter()
            .map(|tri| {
                tri.map(|p| match p {
                    Point::Corner(i) => c[i as usize],
                    Point::Between { a, b, t } => c[a as usize].lerp(c[b as usize], t),
                })
            })
            .collect()
    }

    /// Total signed area (z of the cross products / 2): positive when the
    /// triangles face +z.
    fn area(t: &[[Vec3; 3]]) -> f32 {
        t.iter()
            .map(|[a, b, c]| (*b - *a).cross(*c - *a).z / 2.0)
            .sum()
    }

    fn cut(c: &[Vec3]) -> Vec<[Vec3; 3]> {
        let mut out = Vec::new();
        Triangulator::new().triangulate(c, &mut out);
        resolve(c, &out)
    }

    #[test]
    fn non_convex_polygons_are_cut_exactly_facing_their_way() {
        // An L shape, counter-clockwise: area 3. A fan would cover more.
        let l = flat(&[
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ]);
        let t = cut(&l);
        assert_eq!(t.len(), 4);
        assert!((area(&t) - 3.0).abs() < 1e-6);
        assert!(t.iter().all(|t| area(&[*t]) > 0.0));
        // The same, clockwise: facing −z.
        let mut cw = l.clone();
        cw.reverse();
        assert!((area(&cut(&cw)) + 3.0).abs() < 1e-6);
        // A dart quad, its reflex corner at 2: the other diagonal.
        let dart = flat(&[(0.0, 0.0), (4.0, 0.0), (1.0, 1.0), (0.0, 4.0)]);
        assert!((area(&cut(&dart)) - 4.0).abs() < 1e-6);
    }

    #[test]
    fn repeated_and_collinear_corners_cover_the_outline_once() {
        // A U of area 7 with a repeated corner (a fan from corner 0 covers
        // 11), and a square with a corner in the middle of an edge.
        let u = flat(&[
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 3.0),
            (2.0, 3.0),
            (2.0, 1.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 3.0),
            (0.0, 3.0),
        ]);
        let t = cut(&u);
        assert!((area(&t) - 7.0).abs() < 1e-6, "{}", area(&t));
        assert!(t.iter().all(|t| area(&[*t]) >= 0.0));
        let square = flat(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]);
        assert!((area(&cut(&square)) - 4.0).abs() < 1e-6);
    }

    #[test]
    fn a_folded_quad_is_cut_from_its_first_corner_and_a_flat_bowtie_is_not() {
        // Tux's quad of line 70190, as its file gives it: its halves face
        // apart by either diagonal, and it is folded by 38°.
        let tux = [
            Vec3::new(-0.027591, 0.097889, -0.006308),
            Vec3::new(-0.027654, 0.097883, -0.006316),
            Vec3::new(-0.026971, 0.099459, -0.004736),
            Vec3::new(-0.027139, 0.099196, -0.004921),
        ];
        assert_eq!(quad(tux), Some(0));
        // A flat bowtie, and the same tilted out of the xy plane: flat
        // still, the even-odd rule's.
        let flat =
            [(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0)].map(|(x, y)| Vec3::new(x, y, 0.0));
        assert_eq!(quad(flat), None);
        assert_eq!(quad(flat.map(|p| Vec3::new(p.x, p.y, p.x * 0.5))), None);
        // Lifting one corner by a hair (under 1°) leaves it a bowtie; by a
        // tenth of its size, a fold.
        let lift = |h: f32| {
            let mut q = flat;
            q[1].z = h;
            quad(q)
        };
        assert_eq!(lift(0.001), None);
        assert_eq!(lift(0.2), Some(0));
        // A convex quad and a dart keep their diagonals.
        let square =
            [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Vec3::new(x, y, 0.0));
        assert_eq!(quad(square), Some(0));
        // A dart is cut through its reflex corner, (1, 1), wherever it is.
        let dart =
            [(0.0, 0.0), (4.0, 0.0), (1.0, 1.0), (0.0, 4.0)].map(|(x, y)| Vec3::new(x, y, 0.0));
        assert_eq!(quad(dart), Some(0));
        assert_eq!(quad([dart[1], dart[2], dart[3], dart[0]]), Some(1));
    }

    #[test]
    fn a_bowtie_is_filled_even_odd_inside_its_outline() {
        // Lobes (0,0)-(1,1)-(0,2) and (1,1)-(2,2)-(2,0), area 1 each; the
        // gaps above and below the crossing stay empty.
        let bowtie = flat(&[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0)]);
        let t = cut(&bowtie);
        let total: f32 = t.iter().map(|t| area(&[*t]).abs()).sum();
        assert!((total - 2.0).abs() < 1e-6, "{total}");
        for tri in &t {
            let c = (tri[0] + tri[1] + tri[2]) / 3.0;
            // Inside a lobe: |y − 1| < |x − 1|.
            assert!((c.y - 1.0).abs() < (c.x - 1.0).abs(), "{tri:?}");
        }
        // A pentagram: even-odd leaves its centre pentagon empty.
        let star: Vec<Vec3> = (0..5)
            .map(|k| {
                let a = std::f32::consts::FRAC_PI_2 + k as f32 * 4.0 * std::f32::consts::PI / 5.0;
                Vec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let t = cut(&star);
        assert!(!t.is_empty());
        for tri in &t {
            let c = (tri[0] + tri[1] + tri[2]) / 3.0;
            assert!(
                c.length() > 0.3,
                "the centre is outside by the even-odd rule: {tri:?}"
            );
        }
    }

    #[test]
    fn a_face_of_100k_corners_is_not_quadratic() {
        // An f32 circle (jagged at its last bit): where ear clipping turns
        // quadratic.
        let n = 100_000;
        let ring: Vec<Vec3> = (0..n)
            .map(|i| {
                let a = i as f32 / n as f32 * std::f32::consts::TAU;
                Vec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let t = cut(&ring);
        assert_eq!(t.len(), n - 2);
        assert!((area(&t) - std::f32::consts::PI).abs() < 1e-3);
    }
}

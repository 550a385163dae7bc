//! Meshes: indexed triangles, per-vertex normals, colours by material,
//! and the transform that places them in the world (their lights are in
//! `light.rs`).
//!
//! **Layout.** A [`Mesh`] is a [`Geometry`] (shared: twenty thousand
//! `[[mesh]]` entries naming one shape or file hold one copy) plus what is
//! its own: a colour, a transform, a culling choice. Geometry is stored
//! flat, in the smallest form the renderer reads directly:
//!
//! | data | bytes | |
//! |---|---:|---|
//! | positions | 12 a vertex | f32 x, y, z |
//! | normals | 12 a vertex | f32, unit length |
//! | vertex colours | 6 a vertex | only when the file has them |
//! | texture coordinates | 8 a vertex | only when a material has a texture |
//! | faces | 12 a triangle | u32 vertex indices |
//! | materials | 8 a run | consecutive faces of one colour share a run |
//!
//! so a loaded mesh of `T` triangles on about `T/2` vertices takes about
//! 24 bytes a triangle.
//!
//! **Normals** missing from a file are computed per position, not per vertex
//! index: vertices at the same position (a seam where texture coordinates
//! or normals differ, a model exported with its faces unwelded) share their
//! surroundings, so no seam shows. Each face contributes its normal weighted
//! by its angle at the position (so the normal does not depend on how the
//! surface happens to be split into triangles), but only to corners of
//! faces within the crease angle of it ([`DEFAULT_CREASE`], 60°): the edges
//! of a cube stay sharp, a sphere's seam disappears. A vertex index shared
//! across a crease is split so that each side gets its own normal.
//!
//! **Connectivity** is found once at load, in linear time and without an
//! edge table: positions are welded by a compact hash set
//! ([`PositionSet`]), then around each welded position the positions its
//! corners' edges lead to are listed by a counting sort (4 bytes a corner,
//! dropped once closedness is found, before the normals' tables are made;
//! the normals read only the welded positions, and list again the corners
//! of the few positions with a crease). **Closed** (every edge walked once
//! each way) is that no position leads to itself, and that each edge up
//! (to a higher position) is walked once and has its way back, looked for
//! in its end's list: then every edge is walked once each way (see
//! `Topology::closed`). A
//! closed mesh's Euler characteristic (V − F/2) says at once whether it
//! has a sphere's topology. A model that is not closed shows its inside
//! through the gaps, so it is drawn from both sides by default. **Convex**
//! is decided only when the planner asks (a scene of one closed mesh of a
//! sphere's topology, culled at the back, where it would let the depth test
//! go), and then exactly (see [`Geometry::is_convex`]), from the corners
//! around each position, listed the same way.
//!
//! While a frame is drawn the renderer keeps one transformed vertex per
//! vertex of the mesh being drawn: 14 bytes (clip outcode, snapped screen
//! position and its centre key), and 52 more (depth, 1/w, light, world
//! position, normal, unsnapped screen position) only for a mesh whose
//! faces may read them or that has few vertices for the frame's samples
//! (see `Plan::vertex_extras`); a large model seen small finds the depth
//! and light of a face's corners again where the face has a sample in its
//! box. The framebuffer holds a colour and a depth per sample (8 bytes).

use std::sync::{Arc, OnceLock};

use glam::{DVec3, Mat4, Vec2, Vec3, Vec3A, Vec4};
use rustc_hash::FxHashMap;

use super::anim::{Pose, Rig};
use super::finish::Finish;
use super::light::Light;
use crate::color::{Lin, Rgb};
use crate::texture::Texture;

use super::normals::*;
use super::topology::*;

/// The crease angle: faces meeting at a sharper angle than this keep their
/// own normals at the edge between them.
pub const DEFAULT_CREASE: f32 = 60.0;

/// Faces of one material, from `first` to the next run's first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialRun {
    /// The first face of the run.
    pub first: u32,
    /// The material's colour, in linear light; `None`: the mesh's own
    /// colour.
    pub color: Option<Lin>,
    /// The material's texture, an index into [`Geometry::textures`], which
    /// multiplies the colour (the faces' vertices then have UVs).
    pub texture: Option<u32>,
    /// What its surface does with light beyond its colour.
    pub finish: Finish,
}

/// One run of faces as the renderer draws it: the faces, their colour and
/// their texture.
#[derive(Clone, Debug)]
pub struct Run<'a> {
    /// The faces, as a range of [`Geometry::faces`].
    pub faces: std::ops::Range<usize>,
    /// Their colour (the material's, or the mesh's).
    pub color: Lin,
    /// Their texture, if the material has one.
    pub texture: Option<&'a Texture>,
    /// Their material's finish (plain for faces without a material).
    pub finish: Finish,
}

/// A mesh's shape, in model coordinates: what is shared between meshes.
#[derive(Debug)]
pub struct Geometry {
    /// Where it came from: a file name or a shape, for messages.
    pub name: String,
    /// Vertex positions in model space.
    pub positions: Vec<Vec3>,
    /// One unit normal per position.
    pub normals: Vec<Vec3>,
    /// One colour per position, when the source has them; they override
    /// the face colours.
    pub colors: Option<Vec<Lin>>,
    /// One texture coordinate per position, when the source has them
    /// (`u` right, `v` down the image, as glTF has them).
    pub uvs: Option<Vec<Vec2>>,
    /// A second texture coordinate per position, where a material's maps
    /// read another set than its base colour's (those [`Maps::second`]
    /// marks).
    ///
    /// [`Maps::second`]: crate::scene::Maps::second
    pub uvs2: Option<Vec<Vec2>>,
    /// The textures the material runs name.
    pub textures: Vec<Arc<Texture>>,
    /// Triangles, as indices into `positions` (and `normals`, `colors`).
    pub faces: Vec<[u32; 3]>,
    /// The faces' colours, as runs in face order; empty: every face in the
    /// mesh's colour.
    pub materials: Vec<MaterialRun>,
    /// The bounding box of the positions, `[min, max]` (`None` when a
    /// position is not finite, or there are none).
    pub bounds: Option<[Vec3; 2]>,
    /// Every edge (corners matched by position) shared by exactly two faces
    /// walking it in opposite directions: closed and consistently wound.
    pub closed: bool,
    /// Lines the file draws besides its faces (glTF's line and point
    /// primitives), each a pair of indices into `positions` (a point: the
    /// same index twice) and its colour (`None`: the mesh's).
    pub lines: Vec<([u32; 2], Option<Lin>)>,
    /// Which sides of every face are drawn, where the file says one thing
    /// for all (glTF's `doubleSided`); where its materials differ, each
    /// run's [`Finish::sides`](crate::scene::Finish::sides) says.
    pub sides: crate::scene::Sides,
    /// Closed, in one piece with a sphere's topology.
    sphere_like: bool,
    convex: OnceLock<bool>,
    /// Its edges, found when first drawn (see [`Geometry::edges`]).
    edges: OnceLock<Vec<[u32; 2]>>,
    /// How its vertices move, for a model that animates (the positions and
    /// normals above are its rest pose).
    pub rig: Option<Arc<Rig>>,
    /// The lights the file places, in the same coordinates as the
    /// positions (glTF's `KHR_lights_punctual`); a model shown alone is lit
    /// by them instead of [`Light::rig`].
    pub lights: Vec<Light>,
    /// For a model with normal maps: each face's corners' tangents in
    /// model space (unit `xyz`, and in `w` the sign of the bitangent
    /// `cross(normal, tangent)`), the file's or MikkTSpace's. Per corner,
    /// not per vertex: where UVs are mirrored, a vertex on the mirror line
    /// has a tangent on each side.
    pub tangents: Option<Vec<[Vec4; 3]>>,
}

impl Clone for Geometry {
    fn clone(&self) -> Geometry {
        Geometry {
            name: self.name.clone(),
            positions: self.positions.clone(),
            normals: self.normals.clone(),
            colors: self.colors.clone(),
            uvs: self.uvs.clone(),
            uvs2: self.uvs2.clone(),
            textures: self.textures.clone(),
            faces: self.faces.clone(),
            materials: self.materials.clone(),
            bounds: self.bounds,
            closed: self.closed,
            lines: self.lines.clone(),
            sides: self.sides,
            sphere_like: self.sphere_like,
            convex: self.convex.clone(),
            // Found again when asked: a copy is made to be changed.
            edges: OnceLock::new(),
            rig: self.rig.clone(),
            lights: self.lights.clone(),
            tangents: self.tangents.clone(),
        }
    }
}

impl PartialEq for Geometry {
    fn eq(&self, o: &Geometry) -> bool {
        self.positions == o.positions
            && self.normals == o.normals
            && self.colors == o.colors
            && self.uvs == o.uvs
            && self.uvs2 == o.uvs2
            && self.textures == o.textures
            && self.faces == o.faces
            && self.materials == o.materials
            && self.lights == o.lights
            && self.rig == o.rig
            && self.tangents == o.tangents
    }
}

impl Geometry {
    /// Geometry from positions and faces, with normals computed (see the
    /// module doc) and the facts the planner reads.
    pub fn new(name: impl Into<String>, positions: Vec<Vec3>, faces: Vec<[u32; 3]>) -> Geometry {
        let mut g = Geometry::new_raw(name, positions, faces);
        g.compute_normals(DEFAULT_CREASE);
        g
    }

    /// Geometry as given, normals not computed and facts not found: for
    /// loaders, which set the normals and then call [`Geometry::analyze`].
    pub fn new_raw(
        name: impl Into<String>,
        mut positions: Vec<Vec3>,
        mut faces: Vec<[u32; 3]>,
    ) -> Geometry {
        // A loader's vectors grew by doubling: up to half of each is spare,
        // given back here (in place, for a block this large) before the
        // normals add theirs.
        positions.shrink_to_fit();
        faces.shrink_to_fit();
        Geometry {
            name: name.into(),
            positions,
            normals: Vec::new(),
            colors: None,
            uvs: None,
            uvs2: None,
            textures: Vec::new(),
            faces,
            materials: Vec::new(),
            bounds: None,
            closed: false,
            lines: Vec::new(),
            sides: crate::scene::Sides::Unsaid,
            sphere_like: false,
            convex: OnceLock::new(),
            edges: OnceLock::new(),
            rig: None,
            lights: Vec::new(),
            tangents: None,
        }
    }

    /// Recomputes the bounds and closedness (and forgets convexity); call
    /// it after changing the positions or faces.
    pub fn analyze(&mut self) {
        let mut topo = Topology::new(&self.positions, &self.faces, Listing::Next);
        self.facts(&mut topo);
    }

    /// Sets the facts the planner reads from the mesh's connectivity.
    fn facts(&mut self, topo: &mut Topology) {
        self.bounds = bounds(&self.positions);
        self.closed = self.bounds.is_some() && topo.closed(&self.faces);
        self.sphere_like = self.closed && topo.sphere_like(&self.faces);
        self.convex = OnceLock::new();
        self.edges = OnceLock::new();
    }

    /// The faces in runs of one material, in order, for a mesh coloured
    /// `color`. A texture is given only where the faces have UVs to read
    /// it with.
    pub fn runs(&self, color: Lin) -> impl Iterator<Item = Run<'_>> + '_ {
        let n = self.faces.len();
        let first = self
            .materials
            .first()
            .map_or(n, |r| r.first as usize)
            .min(n);
        let head = (first > 0).then_some(Run {
            faces: 0..first,
            color,
            texture: None,
            finish: Finish::default(),
        });
        head.into_iter()
            .chain(self.materials.iter().enumerate().map(move |(k, r)| {
                let end = self
                    .materials
                    .get(k + 1)
                    .map_or(n, |s| s.first as usize)
                    .min(n);
                Run {
                    faces: (r.first as usize).min(end)..end,
                    color: r.color.unwrap_or(color),
                    texture: self.texture(r.texture),
                    finish: r.finish,
                }
            }))
    }

    /// Texture `index`, when it exists and the vertices have UVs.
    fn texture(&self, index: Option<u32>) -> Option<&Texture> {
        self.uvs.as_ref()?;
        self.textures.get(index? as usize).map(|t| &**t)
    }

    /// Whether any face's material has a highlight (and is lit).
    pub fn shines(&self) -> bool {
        self.materials
            .iter()
            .any(|r| r.finish.specular.is_some() && !r.finish.unlit)
    }

    /// Whether any face's material gives off light.
    pub fn glows(&self) -> bool {
        self.materials
            .iter()
            .any(|r| r.finish.emissive != Lin::BLACK)
    }

    /// Whether any material is masked or blended.
    pub fn sees_through(&self) -> bool {
        use crate::scene::AlphaMode;
        self.materials
            .iter()
            .any(|r| r.finish.alpha.mode != AlphaMode::Opaque)
    }

    /// Whether any material has maps (normal, metallic-roughness,
    /// occlusion or emissive textures) that can be read: the vertices have
    /// UVs.
    pub fn mapped(&self) -> bool {
        self.uvs.is_some() && self.materials.iter().any(|r| !r.finish.maps.is_empty())
    }

    /// Whether any face is drawn with a texture.
    pub fn textured(&self) -> bool {
        self.materials
            .iter()
            .any(|r| self.texture(r.texture).is_some())
    }

    /// The colour of face `f` in a mesh coloured `color`.
    pub fn face_color(&self, f: usize, color: Lin) -> Lin {
        let run = self.materials.partition_point(|r| r.first as usize <= f);
        run.checked_sub(1)
            .and_then(|r| self.materials[r].color)
            .unwrap_or(color)
    }

    /// Closed and convex: its faces seen from one side never overlap on
    /// screen. Decided on first use, exactly: the surface is convex when it
    /// is locally convex everywhere: at every edge the far corner of one
    /// face lies on the inner side of the other face's plane (or on it), by
    /// Shewchuk's exact orientation predicate on the f32 positions, so a
    /// dent of any depth anywhere is found, however far the mesh is from
    /// the origin; at every vertex the faces turn once around it (their
    /// angles sum to at most 2π); and the surface is one piece with the
    /// topology of a sphere (V − E + F = 2). A closed surface that is
    /// locally convex at every point bounds a convex body (Tietze; van
    /// Heijenoort for immersed surfaces). A degenerate face or any doubt
    /// makes the answer no.
    pub fn is_convex(&self) -> bool {
        *self
            .convex
            .get_or_init(|| self.sphere_like && self.bounds.is_some() && convex(self))
    }

    /// Its edges, each once: a pair of vertex indices for each pair of
    /// welded positions that a face joins (vertices at the same position,
    /// split for their normals or texture coordinates, are one; edges of
    /// no length are left out), in order of their welded positions. Found
    /// once (8 bytes an edge, about 12 a face), when a wireframe first
    /// asks.
    pub fn edges(&self) -> &[[u32; 2]] {
        self.edges.get_or_init(|| {
            let (ids, _) = super::topology::weld(&self.positions);
            let id = |i: u32| ids.get(i as usize).copied().unwrap_or(u32::MAX);
            let mut keyed: Vec<([u32; 2], [u32; 2])> = self
                .faces
                .iter()
                .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
                .filter_map(|[a, b]| {
                    let (p, q) = (id(a), id(b));
                    let keyed = if p < q {
                        ([p, q], [a, b])
                    } else {
                        ([q, p], [b, a])
                    };
                    (p != q && p != u32::MAX && q != u32::MAX).then_some(keyed)
                })
                .collect();
            keyed.sort_unstable_by_key(|&(k, _)| k);
            keyed.dedup_by_key(|&mut (k, _)| k);
            keyed.into_iter().map(|(_, e)| e).collect()
        })
    }

    /// Computes the normals per position, splitting at creases sharper
    /// than `crease` degrees (see the module doc); vertex indices shared
    /// across a crease are split, which appends vertices. Also finds the
    /// facts [`Geometry::analyze`] finds, from the same connectivity.
    pub fn compute_normals(&mut self, crease: f32) {
        let mut topo = Topology::new(&self.positions, &self.faces, Listing::Next);
        // Splitting vertices moves no position: the facts found now stand
        // after it. Then the corners lists go before the normals' tables
        // come.
        self.facts(&mut topo);
        topo.forget_corners();
        let (normals, splits) = smooth_normals(&topo, &self.positions, &self.faces, crease);
        drop(topo);
        self.normals = normals;
        // One new vertex for each vertex and normal it must also have.
        let mut copies: FxHashMap<(u32, [u32; 3]), u32> = FxHashMap::default();
        // At most one new vertex a split: room for them at once, not by
        // doubling.
        self.positions.reserve_exact(splits.len());
        self.normals.reserve_exact(splits.len());
        for (face, corner, normal) in splits {
            let v = self.faces[face as usize][corner as usize];
            let key = (v, normal.to_array().map(f32::to_bits));
            let next = self.positions.len() as u32;
            let copy = *copies.entry(key).or_insert(next);
            if copy == next {
                self.positions.push(self.positions[v as usize]);
                if let Some(c) = &mut self.colors {
                    c.push(c[v as usize]);
                }
                for t in [&mut self.uvs, &mut self.uvs2].into_iter().flatten() {
                    t.push(t[v as usize]);
                }
                self.normals.push(normal);
            }
            self.faces[face as usize][corner as usize] = copy;
        }
    }

    /// The centre and radius of a sphere around all finite positions (the
    /// centre of the bounding box, and the farthest position from it), in
    /// f64: any f32 positions, from subnormal to f32's largest, neither
    /// overflow nor underflow here. `None` without a finite position.
    pub fn bounding_sphere(&self) -> Option<(DVec3, f64)> {
        // In f32 lanes: which positions are finite, and the box (the least
        // and the greatest of finite f32s are the same numbers in f64).
        let finite = || {
            self.positions
                .iter()
                .map(|&p| Vec3A::from(p))
                .filter(|p| p.is_finite())
        };
        let first = finite().next()?;
        let (lo, hi) = finite().fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        let centre = lo.as_dvec3() * 0.5 + hi.as_dvec3() * 0.5;
        // The farthest by its squared distance, one root taken: a root
        // correctly rounded never falls as its argument grows, so the
        // largest root is the root of the largest (none is NaN).
        let far = finite()
            .map(|p| p.as_dvec3().distance_squared(centre))
            .fold(0.0f64, |far, d| if d > far { d } else { far });
        Some((centre, far.sqrt()))
    }

    /// Centres the positions on the origin and scales them to fit the unit
    /// sphere, computed in f64 and rounded once, so a model of any size the
    /// file can hold is seen whole.
    pub fn fit_unit_sphere(&mut self) {
        let Some((centre, radius)) = self.bounding_sphere() else {
            return;
        };
        let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
        // The new bounds found as the positions are moved.
        let mut b = Bounds::default();
        for p in &mut self.positions {
            *p = ((p.as_dvec3() - centre) * scale).as_vec3();
            b.add(*p);
        }
        if let Some(rig) = &mut self.rig {
            Arc::make_mut(rig).fitted.push((centre, scale));
        }
        let fit =
            Mat4::from_scale(Vec3::splat(scale as f32)) * Mat4::from_translation(-centre.as_vec3());
        for l in &mut self.lights {
            *l = l.transformed(fit, scale as f32);
        }
        // The same surface, moved and scaled: closedness stands; the bounds
        // and any convexity found are redone.
        self.bounds = b.found();
        self.convex = OnceLock::new();
        self.edges = OnceLock::new();
    }
}

/// A triangle mesh placed in the world: shared geometry, and its own
/// colour, transform and culling.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// The shape, shared between meshes drawn from one file.
    pub geometry: Arc<Geometry>,
    /// The colour of faces whose material gives none.
    pub color: Rgb,
    /// Model to world.
    pub model: Mat4,
    /// Which windings to discard.
    pub cull: Cull,
    /// Where in which clip a moving model is drawn (`None`: at rest, as
    /// is a model that does not move).
    pub pose: Option<Pose>,
}

impl std::ops::Deref for Mesh {
    type Target = Geometry;
    fn deref(&self) -> &Geometry {
        &self.geometry
    }
}

impl Mesh {
    /// A mesh from positions and faces, with normals computed, every face
    /// in `color`, the identity transform and back faces culled.
    pub fn new(
        name: impl Into<String>,
        positions: Vec<Vec3>,
        faces: Vec<[u32; 3]>,
        color: Rgb,
    ) -> Mesh {
        Mesh::of(Arc::new(Geometry::new(name, positions, faces)), color)
    }

    /// A mesh of `geometry` in `color`, identity transform, back faces
    /// culled as the file says ([`Geometry::sides`]), else if the geometry
    /// is closed (an open one shows its inside).
    pub fn of(geometry: Arc<Geometry>, color: Rgb) -> Mesh {
        let cull = match geometry.sides {
            crate::scene::Sides::Single => Cull::Back,
            crate::scene::Sides::Double => Cull::None,
            crate::scene::Sides::Unsaid if geometry.closed => Cull::Back,
            crate::scene::Sides::Unsaid => Cull::None,
        };
        Mesh {
            geometry,
            color,
            model: Mat4::IDENTITY,
            cull,
            pose: None,
        }
    }

    /// The geometry, to change (copied first if another mesh shares it).
    pub fn geometry_mut(&mut self) -> &mut Geometry {
        Arc::make_mut(&mut self.geometry)
    }

    /// The colour of face `f`, in linear light.
    pub fn face_color(&self, f: usize) -> Lin {
        self.geometry.face_color(f, Lin::from_srgb(self.color))
    }

    /// This mesh placed in the world by `model` (model to world), for
    /// building a scene in code.
    #[must_use]
    pub fn with_model(self, model: Mat4) -> Mesh {
        Mesh { model, ..self }
    }

    /// This mesh with the windings `cull` discards.
    #[must_use]
    pub fn with_cull(self, cull: Cull) -> Mesh {
        Mesh { cull, ..self }
    }

    /// This mesh drawn at `time` seconds into clip `clip` of its rig (no
    /// change for a mesh that does not move).
    #[must_use]
    pub fn at(self, clip: usize, time: f64) -> Mesh {
        let pose = self.rig.as_ref().map(|_| Pose { clip, time });
        Mesh { pose, ..self }
    }

    /// Whether drawing this mesh at its pose moves any vertex from the rest
    /// pose: it has a rig, a pose, and the pose's clip animates something
    /// its vertices follow.
    pub fn moves(&self) -> bool {
        match (&self.rig, self.pose) {
            (Some(rig), Some(pose)) => rig.moves(pose.clip),
            _ => false,
        }
    }
}

/// Which triangles to discard by their winding on screen (y up;
/// counter-clockwise faces the viewer, as in OpenGL).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Cull {
    /// Draw both windings.
    #[default]
    None,
    /// Drop clockwise (back-facing) triangles.
    Back,
    /// Drop counter-clockwise (front-facing) triangles.
    Front,
}

crate::choice::choice!(Cull {
    None => "none": "Draw both windings",
    Back => "back": "Drop clockwise (back-facing) triangles",
    Front => "front": "Drop counter-clockwise (front-facing) triangles",
});

/// The bounding box `[min, max]` of `positions`; `None` when one is not
/// finite, or there are none.
/// Drops the faces with a corner whose position is not a finite number,
/// keeping the material runs on the faces they colour. Returns how many
/// positions are not finite and how many faces were dropped, for the
/// loader's note (see [`unfinite_note`]).
#[cfg(any(feature = "gltf", feature = "ply"))]
pub(crate) fn drop_unfinite_faces(
    positions: &[Vec3],
    faces: &mut Vec<[u32; 3]>,
    runs: &mut [MaterialRun],
) -> (usize, usize) {
    let bad = positions.iter().filter(|p| !p.is_finite()).count();
    if bad == 0 {
        return (0, 0);
    }
    let finite = |f: &[u32; 3]| f.iter().all(|&i| positions[i as usize].is_finite());
    // Each run's first face, as a count of the faces kept before it.
    let mut kept = 0u32;
    let mut run = 0;
    let mut out = 0;
    for i in 0..faces.len() {
        while run < runs.len() && runs[run].first as usize == i {
            runs[run].first = kept;
            run += 1;
        }
        if finite(&faces[i]) {
            faces[out] = faces[i];
            out += 1;
            kept += 1;
        }
    }
    for r in &mut runs[run..] {
        r.first = kept;
    }
    let dropped = faces.len() - out;
    faces.truncate(out);
    (bad, dropped)
}

/// The loader's note on what [`drop_unfinite_faces`] dropped, if anything.
#[cfg(any(feature = "gltf", feature = "ply"))]
pub(crate) fn unfinite_note(name: &str, (bad, dropped): (usize, usize)) -> Option<String> {
    (bad > 0).then(|| {
        format!(
            "{name}: {bad} vertices are not finite numbers; the {dropped} faces that use them are not drawn"
        )
    })
}

fn bounds(positions: &[Vec3]) -> Option<[Vec3; 2]> {
    let mut b = Bounds::default();
    positions.iter().for_each(|&p| b.add(p));
    b.found()
}

/// The box around positions, found one at a time in f32 lanes; kept only
/// where every position is finite (then the lanes' `min` and `max` are
/// exact).
struct Bounds {
    lo: Vec3A,
    hi: Vec3A,
    finite: bool,
    any: bool,
}

impl Default for Bounds {
    fn default() -> Bounds {
        Bounds {
            lo: Vec3A::INFINITY,
            hi: Vec3A::NEG_INFINITY,
            finite: true,
            any: false,
        }
    }
}

impl Bounds {
    #[inline]
    fn add(&mut self, p: Vec3) {
        let p = Vec3A::from(p);
        (self.lo, self.hi) = (self.lo.min(p), self.hi.max(p));
        self.finite &= p.is_finite();
        self.any = true;
    }

    /// The box, if there were positions and all were finite.
    fn found(&self) -> Option<[Vec3; 2]> {
        (self.finite && self.any).then(|| [self.lo.into(), self.hi.into()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::Shape;

    #[test]
    fn closed_convex_is_found_only_where_true() {
        let cube = Shape::Cube.mesh(Rgb::WHITE);
        assert!(cube.closed && cube.is_convex());
        assert!(Shape::Sphere.mesh(Rgb::WHITE).is_convex());
        let torus = Shape::Torus.mesh(Rgb::WHITE);
        assert!(torus.closed && !torus.is_convex(), "closed but not convex");
        // A cube with a face missing is not closed.
        let mut open = cube.clone();
        open.geometry_mut().faces.pop();
        open.geometry_mut().analyze();
        assert!(!open.closed && !open.is_convex());
        // A cube with one face wound the wrong way is not consistent.
        let mut flipped = cube.clone();
        let g = flipped.geometry_mut();
        g.faces[0].swap(1, 2);
        g.faces[1].swap(1, 2);
        g.analyze();
        assert!(!flipped.is_convex());
        // A dented cube is closed but not convex.
        let mut dented = cube.clone();
        let g = dented.geometry_mut();
        for p in &mut g.positions {
            if p.y > 0.5 && p.x > 0.5 && p.z > 0.5 {
                *p *= 0.5;
            }
        }
        g.analyze();
        assert!(dented.closed && !dented.is_convex());
        assert_eq!(cube.bounds, Some([Vec3::splat(-0.6), Vec3::splat(0.6)]));
    }

    #[test]
    fn a_fold_is_smooth_below_the_crease_and_split_above_it() {
        // Two triangles on the edge (0,0,0)–(0,0,1), folded by `fold`
        // degrees: near 60° (the crease), where the bound on the fan's sum
        // proves nothing and each face is tested against the mean.
        let shared = |fold: f32| {
            let a = (fold / 2.0).to_radians();
            let positions = vec![
                Vec3::ZERO,
                Vec3::Z,
                Vec3::new(a.cos(), a.sin(), 0.5),
                Vec3::new(-a.cos(), a.sin(), 0.5),
            ];
            let g = Geometry::new("fold", positions, vec![[0, 1, 2], [1, 0, 3]]);
            g.positions.len()
        };
        assert_eq!(shared(50.0), 4, "one normal along the edge");
        assert_eq!(shared(59.0), 4);
        assert_eq!(shared(61.0), 6, "the edge's two vertices split");
        assert_eq!(shared(70.0), 6);
    }

    #[test]
    fn closedness_holds_at_positions_of_many_faces() {
        // A double cone of 40 sides: each apex has 40 faces around it, more
        // than the fans compared in SIMD lanes.
        let n = 40u32;
        let mut positions: Vec<Vec3> = (0..n)
            .map(|i| {
                let a = i as f32 * std::f32::consts::TAU / n as f32;
                Vec3::new(a.cos(), 0.0, a.sin())
            })
            .collect();
        positions.extend([Vec3::Y, -Vec3::Y]);
        let faces: Vec<[u32; 3]> = (0..n)
            .flat_map(|i| [[i, n, (i + 1) % n], [(i + 1) % n, n + 1, i]])
            .collect();
        let cone = Geometry::new("cone", positions.clone(), faces.clone());
        assert!(cone.closed && cone.sphere_like);
        let mut open = faces.clone();
        open.pop();
        assert!(!Geometry::new("open", positions.clone(), open).closed);
        let mut flipped = faces.clone();
        flipped[3].swap(1, 2);
        assert!(!Geometry::new("flipped", positions.clone(), flipped).closed);
        // A face at an apex twice, once each way: every edge still has a
        // reverse, but two faces walk one edge the same way.
        let mut doubled = faces;
        doubled.extend([[0, n, 1], [1, n, 0]]);
        assert!(!Geometry::new("doubled", positions, doubled).closed);
    }

    #[test]
    fn closedness_refuses_an_edge_walked_twice_the_same_way() {
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let tetra = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert!(Geometry::new("tetra", p.clone(), tetra.clone()).closed);
        let mut doubled = tetra.clone();
        doubled.extend([[0, 1, 3], [0, 3, 1]]);
        assert!(!Geometry::new("doubled", p.clone(), doubled).closed);
        // A face with a corner twice: an edge from a position to itself.
        let mut pinched = tetra;
        pinched.extend([[0, 0, 1], [1, 0, 0]]);
        assert!(!Geometry::new("pinched", p, pinched).closed);
        // The same where every position of the doubled faces has more
        // faces around it than are compared in SIMD lanes: the apexes of three
        // closed pyramids of 17 sides, and a triangle between them, both
        // sides, twice.
        let mut p = vec![Vec3::ZERO, Vec3::X * 9.0, Vec3::Y * 9.0];
        let mut faces = Vec::new();
        for apex in 0..3u32 {
            let base = p.len() as u32;
            p.push(p[apex as usize] + Vec3::Z);
            for i in 0..17u32 {
                let a = i as f32 * 0.3;
                p.push(p[apex as usize] + Vec3::new(a.cos(), a.sin(), 1.0));
                let (r, s) = (base + 1 + i, base + 1 + (i + 1) % 17);
                faces.extend([[apex, r, s], [base, s, r]]);
            }
        }
        faces.extend([[0, 1, 2], [0, 2, 1]]);
        assert!(Geometry::new("fans", p.clone(), faces.clone()).closed);
        faces.extend([[0, 1, 2], [0, 2, 1]]);
        assert!(!Geometry::new("fans doubled", p, faces).closed);
    }

    #[test]
    fn normals_of_a_flat_square_point_up_and_fit_is_unit() {
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ];
        let mut m = Geometry::new("sq", p, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(m.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6));
        m.fit_unit_sphere();
        let far = m.positions.iter().map(|p| p.length()).fold(0.0, f32::max);
        assert!((far - 1.0).abs() < 1e-6);
        // Any size an f32 can hold fits the same.
        for size in [1e-30f32, 1e-23, 1e20, 1e30, f32::MAX] {
            let p = vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(size, 0.0, 0.0),
                Vec3::new(size, size, 0.0),
            ];
            let mut m = Geometry::new("t", p, vec![[0, 1, 2]]);
            m.fit_unit_sphere();
            let far = m.positions.iter().map(|p| p.length()).fold(0.0, f32::max);
            assert!((far - 1.0).abs() < 1e-6, "{size}: {far}");
        }
    }

    #[test]
    fn normals_are_shared_at_a_seam_and_split_at_a_crease() {
        // Two faces of a shallow roof meeting at a ridge, each with its own
        // copies of the ridge's vertices: one smooth normal at the ridge.
        let roof = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 0.1, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.5, -0.1, -1.0),
        ];
        let g = Geometry::new("roof", roof, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(g.normals[0], g.normals[4], "the seam is smooth");
        assert_eq!(g.normals[1], g.normals[3]);
        assert_eq!(g.positions.len(), 6);
        // A cube on 8 shared corners: every corner split three ways, each
        // face flat.
        let c = |i: u32| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2 & 1) as f32);
        let faces = vec![
            [0, 2, 3],
            [0, 3, 1],
            [4, 5, 7],
            [4, 7, 6],
            [0, 1, 5],
            [0, 5, 4],
            [2, 6, 7],
            [2, 7, 3],
            [0, 4, 6],
            [0, 6, 2],
            [1, 3, 7],
            [1, 7, 5],
        ];
        let g = Geometry::new("cube", (0..8).map(c).collect(), faces);
        assert_eq!(g.positions.len(), 24, "three normals at each corner");
        for f in &g.faces {
            let n = crate::transform::face_normal(
                g.positions[f[0] as usize],
                g.positions[f[1] as usize],
                g.positions[f[2] as usize],
            );
            assert!(
                f.iter()
                    .all(|&i| (g.normals[i as usize] - n).length() < 1e-6)
            );
        }
        assert!(g.closed && g.is_convex());
    }

    #[test]
    fn the_corner_angle_is_within_1e6_of_atan2() {
        for k in 0..=100_000 {
            let t = std::f32::consts::PI * k as f32 / 100_000.0;
            // A sine as the loader has it: a length, never negative.
            let (sin, cos) = t.sin_cos();
            let sin = sin.abs();
            let want = sin.atan2(cos);
            // Each lane alone, and up to a common factor (a power of two
            // here, as the loader's edges are scaled).
            let got = angles(
                Vec4::new(sin, sin * 4.0, sin / 8.0, sin * 2.0),
                Vec4::new(cos, cos * 4.0, cos / 8.0, cos * 2.0),
            );
            assert!((got.x - want).abs() <= 1e-6, "{t}: {} vs {want}", got.x);
            assert_eq!(got, Vec4::splat(got.x), "{t}");
        }
    }

    #[test]
    fn a_vertex_no_face_uses_gets_plus_z_and_changes_no_other() {
        let tetra = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        let faces = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let alone = Geometry::new("tetra", tetra.clone(), faces.clone());
        // A stray vertex at a place of its own (every vertex its own
        // position), then one at a used vertex's place (welded to it).
        for stray in [Vec3::new(5.0, 5.0, 5.0), tetra[0]] {
            let mut positions = tetra.clone();
            positions.push(stray);
            let g = Geometry::new("tetra", positions, faces.clone());
            assert_eq!(g.normals[4], Vec3::Z, "{stray}");
            assert_eq!(g.normals[..4], alone.normals[..4], "{stray}");
            assert!(g.closed, "{stray}");
        }
    }

    #[test]
    fn four_pow2_factors_in_lanes_are_each_alone() {
        // Every biased exponent (zero and subnormals, normals, infinities
        // and NaNs), with a few mantissas and both signs.
        let numbers: Vec<f32> = (0..=255u32)
            .flat_map(|e| [0, 1, 0x40_0000, 0x7f_ffff].map(|m| f32::from_bits(e << 23 | m)))
            .flat_map(|x| [x, -x])
            .collect();
        for four in numbers.chunks(4) {
            let (s, t, normal) = pow2_factors4(Vec4::from_slice(four));
            for (j, &x) in four.iter().enumerate() {
                let want = crate::transform::pow2_factors(x);
                assert_eq!(normal >> j & 1 == 1, want.is_some(), "{x:e}");
                let (ws, wt) = want.unwrap_or((1.0, 1.0));
                assert_eq!(
                    (s[j].to_bits(), t[j].to_bits()),
                    (ws.to_bits(), wt.to_bits()),
                    "{x:e}"
                );
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]
        /// Four directions in lanes are, bit for bit, each alone (the
        /// loader's means; the frames rest on these bits).
        #[test]
        fn four_directions_in_lanes_are_each_alone(
            xyz in proptest::collection::vec(coordinate(), 12),
        ) {
            let lanes = |axis: usize| Vec4::from_array([0, 1, 2, 3].map(|j| xyz[j * 3 + axis]));
            let four = direction4([lanes(0), lanes(1), lanes(2)]);
            for j in 0..4 {
                let alone = crate::transform::direction(Vec3::from_slice(&xyz[j * 3..j * 3 + 3]));
                let lane = Vec3::new(four[0][j], four[1][j], four[2][j]);
                proptest::prop_assert_eq!(
                    lane.to_array().map(f32::to_bits),
                    alone.to_array().map(f32::to_bits),
                    "vector {}",
                    j
                );
            }
        }
    }

    /// A coordinate for the lanes test: often one of a few values (so
    /// faces repeat corners, lie on a line or on an axis), sometimes any
    /// f32 at all (NaN, infinities, subnormals, the largest).
    fn coordinate() -> impl proptest::strategy::Strategy<Value = f32> {
        use proptest::prelude::*;
        prop_oneof![
            prop::sample::select(vec![0.0, -0.0, 1.0, -1.0, 2.0, 0.5, 3.0]),
            -4.0f32..4.0,
            any::<f32>(),
            prop::sample::select(vec![1e-30, 3e38, -3e38, 1e-42, 7.0e-39]),
        ]
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(4000))]
        /// Four faces in lanes give, bit for bit, what each face gives
        /// alone: the same normal times each angle, the same angles, the
        /// same faces of no area (the loader sums the lanes; the frames of
        /// every model rest on these bits).
        #[test]
        fn four_faces_in_lanes_are_each_face_alone(
            xyz in proptest::collection::vec(coordinate(), 36),
        ) {
            let p = |i: usize| Vec3::new(xyz[i * 3], xyz[i * 3 + 1], xyz[i * 3 + 2]);
            let face = |j: usize| [p(j * 3), p(j * 3 + 1), p(j * 3 + 2)];
            let lanes = |k: usize, axis: usize| {
                Vec4::from_array([0, 1, 2, 3].map(|j| face(j)[k][axis]))
            };
            let corner = |k: usize| [lanes(k, 0), lanes(k, 1), lanes(k, 2)];
            let four = face_weights4([corner(0), corner(1), corner(2)]);
            let bits = |v: Vec4| v.to_array().map(f32::to_bits);
            for j in 0..4 {
                let [a, b, c] = face(j);
                match face_weights(a, b, c) {
                    None => proptest::prop_assert_eq!(four.area >> j & 1, 0, "face {}", j),
                    Some((n, w)) => {
                        proptest::prop_assert_eq!(four.area >> j & 1, 1, "face {}", j);
                        for k in 0..3 {
                            let alone = Vec3::from(n * w[k]).extend(w[k]);
                            proptest::prop_assert_eq!(
                                bits(four.corner[k][j]),
                                bits(alone),
                                "face {} corner {}",
                                j,
                                k
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn weld_numbers_positions_by_first_appearance() {
        let p = |x: f32| Vec3::new(x, 1.0, 2.0);
        let positions = vec![
            p(0.0),
            p(1.0),
            p(-0.0),
            p(1.0),
            p(2.0),
            p(f32::NAN),
            p(f32::NAN),
        ];
        let (ids, n) = weld(&positions);
        // −0.0 and 0.0 are one; a NaN equals a NaN of the same bits.
        assert_eq!(ids, vec![0, 1, 0, 1, 2, 3, 3]);
        assert_eq!(n, 4);
        // Past the starting capacity, the set grows and keeps every id.
        let many: Vec<Vec3> = (0..10_000).map(|i| p((i % 3000) as f32)).collect();
        let (ids, n) = weld(&many);
        assert_eq!(n, 3000);
        assert!(
            ids.iter()
                .enumerate()
                .all(|(i, &id)| id as usize == i % 3000)
        );
    }

    #[test]
    fn twenty_thousand_meshes_of_one_shape_share_one_geometry() {
        let a = Shape::Torus.mesh(Rgb::WHITE);
        let b = Shape::Torus.mesh(Rgb::BLACK);
        assert!(Arc::ptr_eq(&a.geometry, &b.geometry));
        assert_eq!(b.face_color(3), Lin::BLACK);
    }
}

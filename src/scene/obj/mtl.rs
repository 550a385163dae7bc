//! An OBJ file's material library (`mtllib`): each material's diffuse
//! colour (`Kd`, in the colour space the options say), texture (`map_Kd`,
//! with its options) and finish (`Ks` and `Ns`: a highlight; `Ke`: a glow;
//! see [`crate::scene::Finish`]), read under the same checks as the model;
//! what it does not draw (transparency, the other maps) is noted, not
//! silently lost.

use super::*;
use std::path::PathBuf;

/// A material of an MTL file.
#[derive(Clone, Debug, Default)]
pub(super) struct Material {
    /// Its `Kd`.
    pub(super) color: Option<Lin>,
    /// Its `map_Kd`.
    pub(super) map: Option<Map>,
    /// Its `Ks`.
    pub(super) ks: Option<Lin>,
    /// Its `Ns`.
    pub(super) ns: Option<f32>,
    /// Its `Ke` (black without one).
    pub(super) emissive: Lin,
    /// Its `illum` is 0 or 1: no highlight.
    pub(super) dull: bool,
    /// Written by Blender's exporter.
    pub(super) blender: bool,
    /// Its `d` (or 1 − `Tr`), in [0, 1]: below 1, blended.
    pub(super) opacity: Option<f32>,
}

impl Material {
    /// Its finish: a highlight from `Ks` and `Ns` (`Ns` 0 without one:
    /// the broadest) unless `illum` is 0 or 1, a glow from `Ke`. A file
    /// from Blender's exporter means by them its Principled surface's
    /// specular (reflectance 0.08·`Ks`) and roughness (1 − √`Ns` / 30), as
    /// Blender's own importer reads them back.
    pub(super) fn finish(&self) -> crate::scene::Finish {
        use crate::scene::Specular;
        let ns = self.ns.unwrap_or(0.0);
        crate::scene::Finish {
            specular: self.ks.filter(|_| !self.dull).and_then(|ks| {
                let ks = glam::Vec3::from(ks.to_f32()) / 65535.0;
                if self.blender {
                    Specular::blender(ks, ns)
                } else {
                    Specular::phong(ks, ns)
                }
            }),
            emissive: self.emissive,
            unlit: false,
            maps: crate::scene::Maps::default(),
            sides: crate::scene::Sides::Unsaid,
            layers: crate::scene::Layers::default(),
            alpha: match self.opacity {
                Some(d) if d < 1.0 => crate::scene::Alpha {
                    mode: crate::scene::AlphaMode::Blend,
                    factor: d,
                    texture: None,
                },
                _ => crate::scene::Alpha::default(),
            },
        }
    }
}

/// A `map_Kd`: the image, and where the MTL file names it.
#[derive(Clone, Debug)]
pub(super) struct Map {
    pub(super) path: PathBuf,
    /// Why `path` is not where the name points ([`file::Reference::why`]).
    pub(super) why: Option<String>,
    pub(super) sampler: Sampler,
    pub(super) mtl: String,
    pub(super) line: usize,
    pub(super) column: usize,
}

/// A material library: each material's diffuse colour and texture, and
/// notes on the files it names.
#[allow(clippy::type_complexity)]
pub(super) fn mtl(
    file: file::Opened<'_>,
    path: &Path,
    options: &LoadOptions,
) -> Result<(FxHashMap<Vec<u8>, Material>, Vec<String>)> {
    let name = path.display().to_string();
    let at = |line: usize, column: usize, message: String| Error::Parse {
        path: name.clone(),
        line,
        column,
        message,
    };
    let at_byte = |text: &[u8], line: usize, offset: usize, message: String| {
        at(line, lines::column(text, offset), message)
    };
    let mut out = FxHashMap::default();
    let mut notes = Vec::new();
    let mut current: Option<Vec<u8>> = None;
    let mut unread: Vec<&'static str> = Vec::new();
    let mut blender = false;
    let mut lines = Lines::new(file);
    loop {
        let (n, line) = match lines.next_line() {
            Ok(Some(next)) => next,
            Ok(None) => break,
            Err((n, e)) => return Err(at(n, 1, e)),
        };
        // Blender's exporter says so on its first line, and writes its
        // own meaning into `Ks` and `Ns` (see `Material::finish`).
        if n == 1 && line.starts_with(b"# Blender") {
            blender = true;
        }
        let mut c = Cursor::new(line);
        match c.word() {
            Some((b"newmtl", _)) => {
                let m = c.rest().to_vec();
                out.insert(m.clone(), Material::default());
                current = Some(m);
            }
            Some((b"map_Kd", kcol)) => {
                let mut sampler = Sampler::default();
                // Options first (`-clamp on` is read; others are skipped
                // with their arguments, and noted where they would change
                // the picture), then the file name, spaces and all.
                let mut rest = c;
                loop {
                    // Looked at on a copy, taken only if it is an option.
                    let mut next = rest;
                    let Some((w, _)) = next.word().filter(|(w, _)| w.starts_with(b"-")) else {
                        break;
                    };
                    rest = next;
                    // `-o u [v [w]]` (and `-s`, `-t`): the optional two
                    // taken only where they are numbers.
                    let (args, optional) = match w {
                        b"-o" | b"-s" | b"-t" => (1, 2),
                        b"-mm" => (2, 0),
                        _ => (1, 0),
                    };
                    let number = |a: &[u8]| std::str::from_utf8(a).ok()?.parse::<f32>().ok();
                    let mut values = Vec::new();
                    let mut on = false;
                    for _ in 0..args {
                        let arg = rest.word();
                        on = arg.is_some_and(|(a, _)| a == b"on");
                        if w == b"-clamp" && on {
                            sampler.wrap_u = Wrap::ClampToEdge;
                            sampler.wrap_v = Wrap::ClampToEdge;
                        }
                        values.push(arg.and_then(|(a, _)| number(a)));
                    }
                    for _ in 0..optional {
                        let mut next = rest;
                        let Some(x) = next.word().and_then(|(a, _)| number(a)) else {
                            break;
                        };
                        values.push(Some(x));
                        rest = next;
                    }
                    // An option that would move, scale, disturb or
                    // correct the texture, other than at its default, is
                    // said as not drawn (the others change nothing a
                    // `map_Kd` alone draws).
                    let is =
                        |default: &[f32]| values.iter().zip(default).all(|(v, d)| *v == Some(*d));
                    let moves = match w {
                        b"-o" => Some(("map_Kd -o", is(&[0.0; 3]))),
                        b"-s" => Some(("map_Kd -s", is(&[1.0; 3]))),
                        b"-t" => Some(("map_Kd -t", is(&[0.0; 3]))),
                        b"-mm" => Some(("map_Kd -mm", is(&[0.0, 1.0]))),
                        b"-cc" => Some(("map_Kd -cc", !on)),
                        _ => None,
                    };
                    if let Some((key, false)) = moves
                        && !unread.contains(&key)
                    {
                        unread.push(key);
                    }
                }
                let file = rest.rest();
                if file.is_empty() {
                    return Err(at_byte(line, n, kcol, "`map_Kd` names no file".into()));
                }
                let Some(m) = &current else {
                    return Err(at_byte(
                        line,
                        n,
                        kcol,
                        "`map_Kd` before any `newmtl`".into(),
                    ));
                };
                let column = lines::column(line, file.as_ptr() as usize - line.as_ptr() as usize);
                let r =
                    file::reference(path.parent().unwrap_or(Path::new(".")), &name, &lossy(file));
                let map = Map {
                    why: r.why.clone(),
                    path: r.path,
                    sampler,
                    mtl: name.clone(),
                    line: n,
                    column,
                };
                notes.extend(r.note);
                out.entry(m.clone()).or_default().map = Some(map);
            }
            Some((key @ (b"Kd" | b"Ks" | b"Ke"), kcol)) => {
                let key = std::str::from_utf8(key).unwrap_or("K");
                // A colour given as a spectral curve or in CIE XYZ, which
                // the format allows: said as not drawn, the material's
                // colour left as it was.
                let form = c.clone().word().map(|(w, _)| w);
                let other = match (key, form) {
                    ("Kd", Some(b"spectral")) => Some("Kd spectral"),
                    ("Kd", Some(b"xyz")) => Some("Kd xyz"),
                    ("Ks", Some(b"spectral")) => Some("Ks spectral"),
                    ("Ks", Some(b"xyz")) => Some("Ks xyz"),
                    ("Ke", Some(b"spectral")) => Some("Ke spectral"),
                    ("Ke", Some(b"xyz")) => Some("Ke xyz"),
                    _ => None,
                };
                if let Some(other) = other {
                    if !unread.contains(&other) {
                        unread.push(other);
                    }
                    continue;
                }
                let mut v = [0.0f32; 3];
                let mut k = 0;
                while let Some(x) = c.number() {
                    let x = x.ok().filter(|x| x.is_finite() && k < 3);
                    let Some(x) = x else {
                        let (w, col) = c_word_at(line, k + 1);
                        return Err(at_byte(
                            line,
                            n,
                            col,
                            format!("`{key}`: {:?} is not a colour component", lossy(w)),
                        ));
                    };
                    v[k] = x;
                    k += 1;
                }
                if k == 1 {
                    v = [v[0]; 3];
                } else if k != 3 {
                    return Err(at_byte(
                        line,
                        n,
                        kcol,
                        format!("`{key}` needs 3 numbers, found {k}"),
                    ));
                }
                let Some(m) = &current else {
                    return Err(at_byte(
                        line,
                        n,
                        kcol,
                        format!("`{key}` before any `newmtl`"),
                    ));
                };
                let color = options.mtl_colors.decode(v);
                let material = out.entry(m.clone()).or_default();
                match key {
                    "Kd" => material.color = Some(color),
                    "Ks" => material.ks = Some(color),
                    _ => material.emissive = color,
                }
            }
            Some((b"Ns", kcol)) => {
                let Some(Ok(x)) = c.number().filter(|x| x.is_ok_and(f32::is_finite)) else {
                    let (w, col) = c_word_at(line, 1);
                    return Err(at_byte(
                        line,
                        n,
                        if w.is_empty() { kcol } else { col },
                        format!("`Ns`: {:?} is not an exponent", lossy(w)),
                    ));
                };
                let Some(m) = &current else {
                    return Err(at_byte(line, n, kcol, "`Ns` before any `newmtl`".into()));
                };
                out.entry(m.clone()).or_default().ns = Some(x);
            }
            Some((key @ (b"d" | b"Tr" | b"illum"), _)) => {
                // Read for what they say: `d` in [0, 1] (or `Tr`, its
                // complement) is the material's opacity, blended below 1;
                // a value outside it is noted as not drawn.
                let x = c.number().and_then(Result::ok).unwrap_or(f32::NAN);
                let opaque = match key {
                    b"d" => x == 1.0,
                    b"Tr" => x == 0.0,
                    _ => {
                        // `illum` 0 and 1: no highlight, whatever `Ks` says.
                        if let (Some(m), true) = (&current, x == 0.0 || x == 1.0) {
                            out.entry(m.clone()).or_default().dull = true;
                        }
                        true
                    }
                };
                let d = match key {
                    b"d" => Some(("d", x)),
                    b"Tr" => Some(("Tr", 1.0 - x)),
                    _ => None,
                };
                match (d, &current) {
                    // Drawn blended: see `Material::finish`.
                    (Some((_, d)), Some(m)) if (0.0..=1.0).contains(&d) => {
                        out.entry(m.clone()).or_default().opacity = Some(d);
                    }
                    (Some((key, _)), _) if !opaque && !unread.contains(&key) => unread.push(key),
                    _ => {}
                }
            }
            Some((key, _)) => {
                if let Some(&known) = NOT_DRAWN.iter().find(|k| k.as_bytes() == key)
                    && !unread.contains(&known)
                {
                    unread.push(known);
                }
            }
            _ => {}
        }
    }
    if blender {
        out.values_mut().for_each(|m| m.blender = true);
    }
    if !unread.is_empty() {
        notes.push(format!(
            "{}: not drawn: {}",
            crate::text::escape(&name),
            unread
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    Ok((out, notes))
}

/// The statements of a material that rastty reads and does not draw
/// (yet): the maps other than `map_Kd`.
const NOT_DRAWN: &[&str] = &[
    "map_Ks", "map_Ns", "map_d", "map_Ke", "map_Bump", "map_bump", "bump", "norm", "disp", "refl",
];

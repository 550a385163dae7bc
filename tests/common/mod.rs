//! Helpers shared by the integration tests that read rastty's output back
//! through the `vt100` terminal emulator.

#![allow(dead_code)]

use std::num::NonZeroU16;

/// The example model `examples/models/{name}`, held to the bytes its
/// builder `made` (`RASTTY_BLESS=1 cargo test` writes them again): its path.
pub fn example_model(name: &str, made: impl AsRef<[u8]>) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/models")
        .join(name);
    if std::env::var_os("RASTTY_BLESS").is_some() {
        std::fs::write(&path, made.as_ref()).unwrap();
    }
    assert!(
        std::fs::read(&path).unwrap() == made.as_ref(),
        "{} is not what its builder makes (RASTTY_BLESS=1 writes it again)",
        path.display()
    );
    path
}

/// The colours of the samples `scene` covers in a frame of `cols × rows`
/// cells, drawn as users draw it, each once, in order; a frame that covers
/// nothing fails.
pub fn colours(scene: &rastty::scene::Scene, cols: u16, rows: u16) -> Vec<rastty::color::Lin> {
    let mut r = rastty::Renderer::new();
    r.render(
        scene,
        &rastty::RenderOptions {
            cols,
            rows,
            ..rastty::RenderOptions::default()
        },
    );
    let mut c: Vec<_> = r
        .framebuffer()
        .samples()
        .iter()
        .flatten()
        .copied()
        .collect();
    assert!(!c.is_empty(), "the scene covers samples");
    c.sort_by_key(|l| l.0);
    c.dedup();
    c
}

/// A vt100 parser of `rows × cols` cells, no scrollback.
pub fn terminal(rows: u16, cols: u16) -> vt100::Parser {
    vt100::Parser::new(nz(rows), nz(cols), 0)
}

pub fn nz(n: u16) -> NonZeroU16 {
    NonZeroU16::new(n).expect("a non-zero size")
}

/// What a terminal's output processing (ONLCR) makes of lines written with
/// `\n`, without the last newline (so that `n` lines fill an `n`-row
/// terminal without scrolling).
pub fn as_displayed(lines: &[u8]) -> Vec<u8> {
    let lines = lines.strip_suffix(b"\n").unwrap_or(lines);
    let mut out = Vec::with_capacity(lines.len() + lines.len() / 40);
    for &b in lines {
        if b == b'\n' {
            out.push(b'\r');
        }
        out.push(b);
    }
    out
}

/// The cells of a screen as text, foreground and background, each in one
/// form of the picture it shows: a blank's foreground and a full block's
/// background are not shown; a full block is a blank in its colour, and a
/// block element with its complement drawn the other way round (which the
/// encoder may send to keep its pen) is the one with the smaller character.
pub fn cells(screen: &vt100::Screen) -> Vec<(String, vt100::Color, vt100::Color)> {
    use vt100::Color::Default;
    let (rows, cols) = screen.size();
    let mut v = Vec::new();
    for r in 0..rows.get() {
        for c in 0..cols.get() {
            let cell = screen.cell(r, c).unwrap();
            let ch = cell.contents().chars().next().unwrap_or(' ');
            let (fg, bg) = (cell.fgcolor(), cell.bgcolor());
            let (ch, fg, bg) = match (ch, rastty::encode::complement(ch)) {
                (' ', _) => (' ', Default, bg),
                ('█', _) if fg != Default => (' ', Default, fg),
                ('█', _) => ('█', fg, Default),
                (ch, Some(other)) if other < ch && fg != Default && bg != Default => {
                    (other, bg, fg)
                }
                (ch, _) => (ch, fg, bg),
            };
            v.push((ch.to_string(), fg, bg));
        }
    }
    v
}

/// Little-endian bytes of floats.
pub fn f32s(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A GLB file of `json` and the binary chunk `bin`.
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// A unit quad with a colour at each corner, in one PLY encoding.
pub fn quad_ply(format: &str) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat {format} 1.0\ncomment made by rastty's tests\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    let v = [
        ([0.0f32, 0.0, 0.0], [255u8, 0, 0]),
        ([1.0, 0.0, 0.0], [0, 255, 0]),
        ([1.0, 1.0, 0.0], [0, 0, 255]),
        ([0.0, 1.0, 0.0], [255, 255, 255]),
    ];
    match format {
        "ascii" => {
            for (p, c) in v {
                out.extend(
                    format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], c[0], c[1], c[2]).bytes(),
                );
            }
            out.extend(b"4 0 1 2 3\n");
        }
        _ => {
            let be = format == "binary_big_endian";
            for (p, c) in v {
                for x in p {
                    out.extend(if be { x.to_be_bytes() } else { x.to_le_bytes() });
                }
                out.extend(c);
            }
            out.push(4);
            for i in 0i32..4 {
                out.extend(if be { i.to_be_bytes() } else { i.to_le_bytes() });
            }
        }
    }
    out
}

/// An 8-bit RGB PNG of `w × h` pixels, row by row from the top.
pub fn png_rgb(w: u32, h: u32, pixels: &[[u8; 3]]) -> Vec<u8> {
    assert_eq!(pixels.len(), (w * h) as usize);
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().unwrap();
    writer
        .write_image_data(&pixels.iter().flatten().copied().collect::<Vec<u8>>())
        .unwrap();
    writer.finish().unwrap();
    out
}

/// A PNG of 8-bit RGBA pixels.
pub fn png_rgba(w: u32, h: u32, pixels: &[[u8; 4]]) -> Vec<u8> {
    assert_eq!(pixels.len(), (w * h) as usize);
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().unwrap();
    writer
        .write_image_data(&pixels.iter().flatten().copied().collect::<Vec<u8>>())
        .unwrap();
    writer.finish().unwrap();
    out
}

/// A textured mesh as glTF parts: positions, texture coordinates,
/// triangle indices, the image (PNG bytes, or `image_uri` naming it) and
/// the sampler's JSON (`{}` for the defaults).
pub struct TexturedMesh<'a> {
    pub positions: &'a [[f32; 3]],
    pub uvs: &'a [[f32; 2]],
    pub indices: &'a [u32],
    pub png: &'a [u8],
    pub sampler: &'a str,
    pub base_color: [f32; 4],
}

impl TexturedMesh<'_> {
    /// The GLB file: positions, UVs, indices and the image in its binary
    /// chunk.
    pub fn glb(&self) -> Vec<u8> {
        let (json, bin) = self.parts(None);
        glb(&json, &bin)
    }

    /// The JSON (with the image in the buffer unless `image_uri` names a
    /// file) and the binary buffer.
    pub fn parts(&self, image_uri: Option<&str>) -> (String, Vec<u8>) {
        let mut bin = f32s(&self.positions.concat());
        let uv_at = bin.len();
        bin.extend(f32s(&self.uvs.concat()));
        let idx_at = bin.len();
        bin.extend(self.indices.iter().flat_map(|i| i.to_le_bytes()));
        let png_at = bin.len();
        if image_uri.is_none() {
            bin.extend_from_slice(self.png);
        }
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let (lo, hi) = self.positions.iter().fold(
            ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                    [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
                )
            },
        );
        let n = self.positions.len();
        let image = match image_uri {
            Some(uri) => format!(r#"{{"uri":"{uri}"}}"#),
            None => r#"{"bufferView":3,"mimeType":"image/png"}"#.to_string(),
        };
        let png_view = match image_uri {
            Some(_) => String::new(),
            None => format!(
                r#",{{"buffer":0,"byteOffset":{png_at},"byteLength":{}}}"#,
                self.png.len()
            ),
        };
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
            "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":0}}]}}],
            "materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":{:?},"baseColorTexture":{{"index":0}}}}}}],
            "textures":[{{"source":0,"sampler":0}}],
            "samplers":[{}],
            "images":[{image}],
            "buffers":[{{"byteLength":{}}}],
            "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{uv_at}}},
                           {{"buffer":0,"byteOffset":{uv_at},"byteLength":{}}},
                           {{"buffer":0,"byteOffset":{idx_at},"byteLength":{}}}{png_view}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3","min":{lo:?},"max":{hi:?}}},
                         {{"bufferView":1,"componentType":5126,"count":{n},"type":"VEC2"}},
                         {{"bufferView":2,"componentType":5125,"count":{},"type":"SCALAR"}}]}}"#,
            self.base_color,
            self.sampler,
            bin.len(),
            idx_at - uv_at,
            self.indices.len() * 4,
            self.indices.len(),
        );
        (json, bin)
    }
}

/// The example model `examples/models/finishes.glb`: three squares side by
/// side, each a material with a finish the planner decides on apart: one
/// that glows red (`emissiveFactor`), one blue and half see-through
/// (`alphaMode` BLEND), one with a normal map of bumps (its tangents made by
/// MikkTSpace). The witness of the glow, alpha and maps effects.
pub fn finishes_glb() -> Vec<u8> {
    let mut d = Doc::default();
    let square = |x: f32| {
        [[-0.45, -0.45], [0.45, -0.45], [0.45, 0.45], [-0.45, 0.45]].map(|[u, v]| [u + x, v, 0.0])
    };
    let uv: Vec<f32> = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]].concat();
    let mut prims = Vec::new();
    for (k, x) in [-1.0f32, 0.0, 1.0].into_iter().enumerate() {
        let pos = d.vec3(&square(x));
        let normal = d.vec3(&[[0.0, 0.0, 1.0]; 4]);
        let uv = d.floats(&uv, "VEC2", 2);
        let idx = d.indices(&[[0, 1, 2], [0, 2, 3]]);
        prims.push(format!(
            r#"{{"attributes":{{"POSITION":{pos},"NORMAL":{normal},"TEXCOORD_0":{uv}}},"indices":{idx},"material":{k}}}"#
        ));
    }
    // Bumps: normals tilted every way over a 4×4 map.
    let bumps: Vec<[u8; 3]> = (0..16)
        .map(|i| {
            let (x, y) = (i % 4, i / 4);
            [
                if x % 2 == 0 { 80 } else { 176 },
                if y % 2 == 0 { 80 } else { 176 },
                230,
            ]
        })
        .collect();
    let view = d.view(&png_rgb(4, 4, &bumps));
    d.glb(&format!(
        r#""materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0.4,0.4,0.4,1]}},"emissiveFactor":[1,0.1,0]}},
{{"pbrMetallicRoughness":{{"baseColorFactor":[0.1,0.3,1,0.5]}},"alphaMode":"BLEND"}},
{{"pbrMetallicRoughness":{{"baseColorFactor":[0.9,0.9,0.9,1]}},"normalTexture":{{"index":0}}}}],
"samplers":[{{"magFilter":9729,"minFilter":9729}}],
"images":[{{"bufferView":{view},"mimeType":"image/png"}}],"textures":[{{"source":0,"sampler":0}}],
"meshes":[{{"primitives":[{}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#,
        prims.join(",")
    ))
}

/// The example model `examples/models/crate.glb`: a cube two units on a
/// side, each face carrying the whole of a 64×64 crate texture (planks, a
/// frame and a diagonal brace, made here), nearest-magnified so that its
/// texels stay crisp up close and trilinear when minified.
pub fn crate_glb() -> Vec<u8> {
    // Each face: its normal, and the directions of the texture's right and
    // up on it (right × up = normal, so the corners run counter-clockwise).
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
    ];
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    let mut indices = Vec::new();
    for (n, r, u) in faces {
        let base = positions.len() as u32;
        for (sr, su, uv) in [
            (-1.0, -1.0, [0.0, 1.0]),
            (1.0, -1.0, [1.0, 1.0]),
            (1.0, 1.0, [1.0, 0.0]),
            (-1.0, 1.0, [0.0, 0.0]),
        ] {
            positions.push(std::array::from_fn(|k| n[k] + sr * r[k] + su * u[k]));
            uvs.push(uv);
        }
        indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
    }
    let texels: Vec<[u8; 3]> = (0..64 * 64u32)
        .map(|k| {
            let (x, y) = (k % 64, k / 64);
            // A little grain: a hash of the texel, ±8.
            let h = (x.wrapping_mul(374_761_393) ^ y.wrapping_mul(668_265_263))
                .wrapping_mul(2_246_822_519);
            let grain = (h >> 28) as i32 - 8;
            let shade = |c: [i32; 3], d: i32| c.map(|v| (v + d).clamp(0, 255) as u8);
            let frame = !(6..58).contains(&x) || !(6..58).contains(&y);
            let brace = (x as i32 - y as i32).abs() < 5;
            if frame || brace {
                let edge =
                    x == 6 || x == 57 || y == 6 || y == 57 || (x as i32 - y as i32).abs() == 4;
                shade([122, 78, 38], grain - if edge { 40 } else { 0 })
            } else {
                let plank = y / 9;
                let seam = y % 9 == 0;
                let tone = if plank % 2 == 0 {
                    [176, 124, 66]
                } else {
                    [160, 110, 56]
                };
                shade(tone, grain - if seam { 60 } else { 0 })
            }
        })
        .collect();
    TexturedMesh {
        positions: &positions,
        uvs: &uvs,
        indices: &indices,
        png: &png_rgb(64, 64, &texels),
        sampler: r#"{"magFilter":9728,"minFilter":9987}"#,
        base_color: [1.0; 4],
    }
    .glb()
}

/// A glTF document's binary chunk and the JSON of its buffer views and
/// accessors, built up one array at a time.
#[derive(Default)]
pub struct Doc {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
}

impl Doc {
    /// Appends `bytes` as a buffer view and an accessor of `count`
    /// elements of `kind` (`"VEC3"`, …) and `component` (5126: f32, 5123:
    /// u16); returns the accessor's index.
    pub fn add(&mut self, bytes: Vec<u8>, count: usize, kind: &str, component: u32) -> usize {
        self.add_bounded(bytes, count, kind, component, "")
    }

    /// [`Doc::add`] with `extra` JSON members (`,"min":…,"max":…`).
    pub fn add_bounded(
        &mut self,
        bytes: Vec<u8>,
        count: usize,
        kind: &str,
        component: u32,
        extra: &str,
    ) -> usize {
        self.view(&bytes);
        self.accessors.push(format!(
            r#"{{"bufferView":{},"componentType":{component},"count":{count},"type":"{kind}"{extra}}}"#,
            self.views.len() - 1
        ));
        self.accessors.len() - 1
    }

    /// Appends `bytes` (an image) as a buffer view alone; returns the
    /// view's index.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views.push(format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
            self.bin.len(),
            bytes.len()
        ));
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    /// Appends an accessor written whole (`{…}`, naming views this
    /// document has); returns its index.
    pub fn accessor(&mut self, json: String) -> usize {
        self.accessors.push(json);
        self.accessors.len() - 1
    }

    pub fn vec3(&mut self, v: &[[f32; 3]]) -> usize {
        self.floats(v.as_flattened(), "VEC3", 3)
    }

    /// Floats, `per` a element, with their bounds (which the format asks
    /// of positions and key times).
    pub fn floats(&mut self, v: &[f32], kind: &str, per: usize) -> usize {
        let bound = |pick: fn(f32, f32) -> f32| {
            (0..per)
                .map(|k| {
                    let b = v
                        .iter()
                        .skip(k)
                        .step_by(per)
                        .copied()
                        .reduce(pick)
                        .unwrap_or(0.0);
                    if b.is_finite() {
                        format!("{b:?}")
                    } else {
                        "0.0".into()
                    }
                })
                .collect::<Vec<_>>()
                .join(",")
        };
        let extra = format!(
            r#","min":[{}],"max":[{}]"#,
            bound(f32::min),
            bound(f32::max)
        );
        self.add_bounded(f32s(v), v.len() / per, kind, 5126, &extra)
    }

    pub fn indices(&mut self, faces: &[[u16; 3]]) -> usize {
        let bytes = faces
            .as_flattened()
            .iter()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        self.add(bytes, faces.len() * 3, "SCALAR", 5123)
    }

    /// The GLB of `rest` (the JSON after `"asset"`, `"buffers"`,
    /// `"bufferViews"` and `"accessors"`).
    pub fn glb(&self, rest: &str) -> Vec<u8> {
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}],"bufferViews":[{}],"accessors":[{}],{rest}}}"#,
            self.bin.len().next_multiple_of(4),
            self.views.join(","),
            self.accessors.join(",")
        );
        glb(&json, &self.bin)
    }
}

/// The example model `examples/models/metals.glb`: three spheres in a
/// row, each a metal of its own (`metallicFactor` 1): polished gold
/// (roughness 0.1), brushed silver (0.4) and rough copper (0.8). The
/// witness of the environment's reflection.
pub fn metals_glb() -> Vec<u8> {
    spheres_glb(
        r#"{"pbrMetallicRoughness":{"baseColorFactor":[1.0,0.766,0.336,1],"metallicFactor":1,"roughnessFactor":0.1}},
{"pbrMetallicRoughness":{"baseColorFactor":[0.972,0.960,0.915,1],"metallicFactor":1,"roughnessFactor":0.4}},
{"pbrMetallicRoughness":{"baseColorFactor":[0.955,0.638,0.538,1],"metallicFactor":1,"roughnessFactor":0.8}}"#,
        "",
    )
}

/// The example model `examples/models/layers.glb`: three spheres in a row
/// of the layer extensions, a red paint under a clear coat
/// (`KHR_materials_clearcoat`), a navy velvet with a pale sheen
/// (`KHR_materials_sheen`) and a white plastic of index 1.8 with a gold
/// specular tint (`KHR_materials_ior`, `KHR_materials_specular`). The
/// witness of the clearcoat and sheen effects.
pub fn layers_glb() -> Vec<u8> {
    spheres_glb(
        r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.6,0.02,0.02,1],"metallicFactor":0,"roughnessFactor":0.6},"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":1,"clearcoatRoughnessFactor":0.05}}},
{"pbrMetallicRoughness":{"baseColorFactor":[0.02,0.03,0.2,1],"metallicFactor":0,"roughnessFactor":0.9},"extensions":{"KHR_materials_sheen":{"sheenColorFactor":[0.7,0.75,1.0],"sheenRoughnessFactor":0.4}}},
{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.9,0.9,1],"metallicFactor":0,"roughnessFactor":0.3},"extensions":{"KHR_materials_ior":{"ior":1.8},"KHR_materials_specular":{"specularColorFactor":[1.0,0.8,0.3]}}}"#,
        r#""extensionsUsed":["KHR_materials_clearcoat","KHR_materials_sheen","KHR_materials_ior","KHR_materials_specular"],"#,
    )
}

/// Three unit spheres in a row along x (16 rings of 32 segments), of
/// `materials` (three, JSON), with `extra` (top-level JSON members, each
/// followed by a comma) before the rest.
fn spheres_glb(materials: &str, extra: &str) -> Vec<u8> {
    let mut d = Doc::default();
    let (rings, segments) = (16u16, 32u16);
    let mut unit = Vec::new();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * f32::from(i) / f32::from(rings);
        for j in 0..=segments {
            let phi = std::f32::consts::TAU * f32::from(j) / f32::from(segments);
            unit.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ]);
        }
    }
    let row = segments + 1;
    let mut faces = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b) = (i * row + j, (i + 1) * row + j);
            if i > 0 {
                faces.push([a, b, a + 1]);
            }
            if i + 1 < rings {
                faces.push([a + 1, b, b + 1]);
            }
        }
    }
    let mut prims = Vec::new();
    for (k, x) in [-2.2f32, 0.0, 2.2].into_iter().enumerate() {
        let pos: Vec<[f32; 3]> = unit.iter().map(|&[a, b, c]| [a + x, b, c]).collect();
        let pos = d.vec3(&pos);
        let normal = d.vec3(&unit);
        let idx = d.indices(&faces);
        prims.push(format!(
            r#"{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx},"material":{k}}}"#
        ));
    }
    d.glb(&format!(
        r#"{extra}"materials":[{materials}],
"meshes":[{{"primitives":[{}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#,
        prims.join(",")
    ))
}

/// The example model `examples/models/lines.gltf` (its buffer a data
/// URI): a grey triangle with glTF's line and point primitives around it,
/// a red square outline (LINE_LOOP), green diagonals (LINES), a blue
/// zigzag (LINE_STRIP) and a grid of white points (POINTS), each in its
/// material's colour. The witness of the lines effect.
pub fn lines_gltf() -> String {
    use base64::Engine as _;
    let mut d = Doc::default();
    let tri = d.vec3(&[[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.0, 0.5, 0.0]]);
    let square = d.vec3(&[
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ]);
    let diagonals = d.vec3(&[
        [-0.9, -0.9, 0.1],
        [0.9, 0.9, 0.1],
        [-0.9, 0.9, 0.1],
        [0.9, -0.9, 0.1],
    ]);
    let zigzag: Vec<[f32; 3]> = (0..7)
        .map(|i| {
            [
                -1.2 + 0.4 * i as f32,
                if i % 2 == 0 { 1.2 } else { 1.4 },
                0.0,
            ]
        })
        .collect();
    let zigzag = d.vec3(&zigzag);
    let grid: Vec<[f32; 3]> = (0..25)
        .map(|i| {
            [
                -1.2 + 0.6 * (i % 5) as f32,
                -1.2 + 0.6 * (i / 5) as f32,
                -0.1,
            ]
        })
        .collect();
    let grid = d.vec3(&grid);
    let prim = |pos: usize, mode: u32, material: usize| {
        format!(r#"{{"attributes":{{"POSITION":{pos}}},"mode":{mode},"material":{material}}}"#)
    };
    let prims = [
        prim(tri, 4, 0),
        prim(square, 2, 1),
        prim(diagonals, 1, 2),
        prim(zigzag, 3, 3),
        prim(grid, 0, 4),
    ];
    let (json_bin, bin) = {
        let glb = d.glb("\"scenes\":[]");
        // The GLB's chunks: its JSON's views and accessors, and its binary.
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        let json: serde_json::Value = serde_json::from_str(
            std::str::from_utf8(&glb[20..20 + json_len])
                .unwrap()
                .trim_end(),
        )
        .unwrap();
        (json, glb[20 + json_len + 8..].to_vec())
    };
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let color = |c: [f32; 3]| {
        format!(
            r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[{},{},{},1]}}}}"#,
            c[0], c[1], c[2]
        )
    };
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{}]}}],
"materials":[{},{},{},{},{}],
"buffers":[{{"byteLength":{},"uri":"{uri}"}}],
"bufferViews":{},
"accessors":{}}}
"#,
        prims.join(","),
        color([0.5, 0.5, 0.5]),
        color([1.0, 0.0, 0.0]),
        color([0.0, 1.0, 0.0]),
        color([0.0, 0.2, 1.0]),
        color([1.0, 1.0, 1.0]),
        bin.len(),
        json_bin["bufferViews"],
        json_bin["accessors"],
    )
}

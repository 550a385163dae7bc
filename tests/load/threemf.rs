//! 3MF end to end, on archives the tests write: objects, components and
//! build items placed by their transforms in metres, colours from base
//! materials and colour groups, and the archive's hostile cases (a part
//! that unpacks past the budget, a model part outside the archive's root,
//! cycles of components, damaged bytes) refused with a message.

use std::io::Write;

use glam::Vec3;
use rastty::color::{Lin, Rgb};
use rastty::scene::{LoadOptions, threemf};

/// The package's relationships, naming `target` as the model part.
fn rels(target: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
<Relationship Target="{target}" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>"#
    )
}

/// A zip of `parts` (name, text), deflated.
fn archive(parts: &[(&str, &str)]) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut out);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, text) in parts {
        zip.start_file(*name, options).unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    zip.finish().unwrap();
    out.into_inner()
}

/// A package whose model part is `model`.
fn package(model: &str) -> Vec<u8> {
    archive(&[
        ("_rels/.rels", &rels("/3D/3dmodel.model")),
        ("3D/3dmodel.model", model),
    ])
}

/// A model in `unit` of a red triangle (a base material) and a triangle
/// whose corners are three colours of a colour group, as object 1; object
/// 2 placing object 1 twice (moved 10 along x, and turned a quarter about
/// z); and a build item placing object 2 moved 100 up z.
fn model(unit: &str) -> String {
    format!(
        r##"<?xml version="1.0" encoding="UTF-8"?>
<model unit="{unit}" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" xmlns:m="http://schemas.microsoft.com/3dmanufacturing/material/2015/02">
 <resources>
  <basematerials id="5"><base name="red" displaycolor="#FF0000"/><base name="green" displaycolor="#00FF00FF"/></basematerials>
  <m:colorgroup id="6"><m:color color="#0000FF"/><m:color color="#FFFFFF"/><m:color color="#000000"/></m:colorgroup>
  <object id="1" type="model" pid="5" pindex="0">
   <mesh>
    <vertices>
     <vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="1" y="1" z="0"/>
    </vertices>
    <triangles>
     <triangle v1="0" v2="1" v3="2"/>
     <triangle v1="1" v2="3" v3="2" pid="6" p1="0" p2="1" p3="2"/>
    </triangles>
   </mesh>
  </object>
  <object id="2" type="model">
   <components>
    <component objectid="1" transform="1 0 0 0 1 0 0 0 1 10 0 0"/>
    <component objectid="1" transform="0 1 0 -1 0 0 0 0 1 0 0 0"/>
   </components>
  </object>
 </resources>
 <build><item objectid="2" transform="1 0 0 0 1 0 0 0 1 0 0 100"/></build>
</model>"##
    )
}

#[test]
fn objects_components_and_items_are_placed_by_their_transforms_in_metres() {
    let loaded = threemf::parse(&package(&model("millimeter")), "t.3mf").unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let g = &loaded.geometry;
    assert_eq!(g.faces.len(), 4);
    // Each placement's four vertices in millimetres, plus the corners
    // whose colours differ from their vertex's first (vertex 1 and 2 of
    // the coloured triangle are red in the first triangle).
    let mm = |x: f32, y: f32, z: f32| Vec3::new(x, y, z) * 1e-3;
    let placed: Vec<Vec3> = g
        .faces
        .iter()
        .flatten()
        .map(|&i| g.positions[i as usize])
        .collect();
    let want = [
        // Moved 10 along x, 100 up z.
        [
            mm(10.0, 0.0, 100.0),
            mm(11.0, 0.0, 100.0),
            mm(10.0, 1.0, 100.0),
        ],
        [
            mm(11.0, 0.0, 100.0),
            mm(11.0, 1.0, 100.0),
            mm(10.0, 1.0, 100.0),
        ],
        // Turned a quarter about z ((x, y) → (−y, x)), 100 up z.
        [
            mm(0.0, 0.0, 100.0),
            mm(0.0, 1.0, 100.0),
            mm(-1.0, 0.0, 100.0),
        ],
        [
            mm(0.0, 1.0, 100.0),
            mm(-1.0, 1.0, 100.0),
            mm(-1.0, 0.0, 100.0),
        ],
    ];
    for (got, want) in placed.iter().zip(want.as_flattened()) {
        assert!(
            (*got - *want).abs().max_element() < 1e-9,
            "{got} against {want}"
        );
    }
    // Red, then blue, white and black by corner.
    let colours = g.colors.as_ref().expect("coloured");
    let corner: Vec<Lin> = g
        .faces
        .iter()
        .flatten()
        .map(|&i| colours[i as usize])
        .collect();
    let c = |r, g, b| Lin::from_srgb(Rgb::new(r, g, b));
    let red = c(255, 0, 0);
    assert_eq!(
        corner[..6],
        [red, red, red, c(0, 0, 255), c(255, 255, 255), c(0, 0, 0)]
    );
    assert_eq!(corner[6..9], [red; 3]);
}

#[test]
fn units_are_turned_into_metres() {
    for (unit, metres) in [
        ("micron", 1e-6),
        ("centimeter", 1e-2),
        ("inch", 0.0254),
        ("meter", 1.0),
    ] {
        let g = threemf::parse(&package(&model(unit)), "t.3mf")
            .unwrap()
            .geometry;
        let z = g.positions[0].z;
        assert!((z - 100.0 * metres).abs() <= 1e-6 * z.abs(), "{unit}: {z}");
    }
    let e = threemf::parse(&package(&model("furlong")), "t.3mf")
        .err()
        .map(|e| e.to_string());
    assert!(e.is_some_and(|e| e.contains("3D/3dmodel.model:2:") && e.contains("furlong")));
}

#[test]
fn what_is_not_drawn_is_said_in_one_note() {
    let m = model("millimeter").replace(
        "</resources>",
        r#"<m:texture2dgroup id="9" texid="1"/></resources>"#,
    );
    let loaded = threemf::parse(&package(&m), "t.3mf").unwrap();
    assert_eq!(loaded.notes, ["t.3mf: not drawn: textures"]);
}

#[test]
fn a_part_that_unpacks_past_the_budget_is_refused_before_it_is_unpacked() {
    // 4 MB of spaces in the model deflate to a few kilobytes.
    let big = model("millimeter").replace("<build>", &format!("{}<build>", " ".repeat(4 << 20)));
    let file = package(&big);
    assert!(file.len() < 64 << 10, "{} bytes", file.len());
    let options = LoadOptions {
        max_bytes: 1 << 20,
        ..LoadOptions::default()
    };
    let Err(e) = rastty::scene::threemf::parse_with(&file, "bomb.3mf", &options) else {
        panic!("read past the budget")
    };
    assert!(e.to_string().contains("more than the budget"), "{e}");
}

#[test]
fn a_model_part_outside_the_archive_or_a_cycle_is_refused() {
    let outside = archive(&[
        ("_rels/.rels", &rels("/../3D/3dmodel.model")),
        ("3D/3dmodel.model", &model("millimeter")),
    ]);
    let e = threemf::parse(&outside, "t.3mf").err().unwrap().to_string();
    assert!(e.contains("not a name inside the archive"), "{e}");
    let cycle = model("millimeter").replace(
        r#"<component objectid="1" transform="1 0 0 0 1 0 0 0 1 10 0 0"/>"#,
        r#"<component objectid="2"/>"#,
    );
    let e = threemf::parse(&package(&cycle), "t.3mf")
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("nest deeper"), "{e}");
    let missing = archive(&[("_rels/.rels", &rels("/3D/3dmodel.model"))]);
    let e = threemf::parse(&missing, "t.3mf").err().unwrap().to_string();
    assert!(e.contains("no part 3D/3dmodel.model"), "{e}");
}

#[test]
fn damaged_archives_are_refused_never_a_panic() {
    let file = package(&model("millimeter"));
    let mut seed = 3u64;
    let mut refused = 0;
    for t in 0..300 {
        let mut b = file.clone();
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let i = (seed >> 33) as usize % b.len();
        if t % 3 == 0 {
            b.truncate(i);
        } else {
            b[i] ^= (seed >> 20) as u8 | 1;
        }
        if threemf::parse(&b, "t.3mf").is_err() {
            refused += 1;
        }
    }
    assert!(refused > 100, "{refused} of 300 refused");
}

#[test]
fn components_in_other_model_parts_are_read_as_slicers_write_them() {
    // Object 1 in a part of its own (the production extension, as Bambu
    // Studio writes it), placed from the root by `p:path`: the same
    // triangles as the one-part model.
    let one = threemf::parse(&package(&model("millimeter")), "t.3mf")
        .unwrap()
        .geometry;
    let m = model("millimeter");
    let (head, rest) = m.split_once(r#"<object id="1""#).unwrap();
    let (object, tail) = rest.split_once("</object>").unwrap();
    let groups_end = head.rfind("</m:colorgroup>").unwrap() + "</m:colorgroup>".len();
    let part = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" xmlns:m="http://schemas.microsoft.com/3dmanufacturing/material/2015/02"><resources>{}<object id="1"{object}</object></resources><build/></model>"#,
        &head[head.find("<basematerials").unwrap()..groups_end]
    );
    let p = r#" xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06" p:path="/3D/Objects/part.model""#;
    let root = format!("{head}{tail}")
        .replace(
            r#"objectid="1" transform="1"#,
            &format!(r#"objectid="1"{p} transform="1"#),
        )
        .replace(
            r#"objectid="1" transform="0"#,
            &format!(r#"objectid="1"{p} transform="0"#),
        );
    let file = archive(&[
        ("_rels/.rels", &rels("/3D/3dmodel.model")),
        ("3D/3dmodel.model", &root),
        ("3D/Objects/part.model", &part),
    ]);
    let two = threemf::parse(&file, "t.3mf").unwrap().geometry;
    assert_eq!(two.positions, one.positions);
    assert_eq!(two.faces, one.faces);
    assert_eq!(two.colors, one.colors);
    // A part named outside the archive's root is refused.
    let bad = root.replace("/3D/Objects/part.model", "/3D/../../part.model");
    let file = archive(&[
        ("_rels/.rels", &rels("/3D/3dmodel.model")),
        ("3D/3dmodel.model", &bad),
    ]);
    let e = threemf::parse(&file, "t.3mf").err().unwrap().to_string();
    assert!(e.contains("not a part inside the archive"), "{e}");
}

#[test]
fn a_3mf_file_is_told_by_its_name_and_stood_up_as_stl_is() {
    // Written where the tests write, then read as `rastty render` reads a
    // model: by its extension, z-up turned onto y.
    let dir = std::env::temp_dir().join(format!("rastty-3mf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("model.3mf");
    std::fs::write(&path, package(&model("millimeter"))).unwrap();
    let scene = rastty::scene::Scene::of_model(&path).unwrap();
    let z_up = glam::Mat4::from_cols(glam::Vec4::X, -glam::Vec4::Z, glam::Vec4::Y, glam::Vec4::W);
    assert_eq!(scene.meshes[0].model, z_up);
    assert_eq!(scene.meshes[0].geometry.faces.len(), 4);
    // Without its extension, its first bytes (a zip's) say what it is.
    let bare = dir.join("model");
    std::fs::rename(&path, &bare).unwrap();
    let scene = rastty::scene::Scene::of_model(&bare).unwrap();
    assert_eq!(scene.meshes[0].geometry.faces.len(), 4);
    std::fs::remove_dir_all(&dir).unwrap();
}

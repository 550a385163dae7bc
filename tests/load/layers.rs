//! A material's layers end to end: the example model is what its builder
//! makes, and a clear coat's and a sheen's samples are what the spec's
//! formulas, written again here in f64, say.

use crate::common;

use std::sync::Arc;

use glam::{DVec3, Vec3};
use rastty::color::Rgb;
use rastty::scene::environment::Environment;
use rastty::scene::{Camera, LoadOptions, Mesh, Projection, Scene, gltf};

#[test]
fn the_example_layers_are_what_their_builder_makes() {
    let path = common::example_model("layers.glb", common::layers_glb());
    let loaded = gltf::load(&path, &LoadOptions::default()).unwrap();
    assert!(loaded.notes.is_empty(), "{:?}", loaded.notes);
    let m = &loaded.geometry.materials;
    let coat = m[0].finish.layers.clearcoat.unwrap();
    assert_eq!((coat.factor, coat.roughness), (1.0, 0.05));
    let sheen = m[1].finish.layers.sheen.unwrap();
    assert_eq!(
        (sheen.color, sheen.roughness),
        (Vec3::new(0.7, 0.75, 1.0), 0.4)
    );
    // Index 1.8 and a gold tint: ((1.8 − 1) / 2.8)² times the tint.
    let s = m[2].finish.specular.unwrap();
    let r = (0.8f32 / 2.8).powi(2);
    assert!(
        (s.reflectance - Vec3::new(1.0, 0.8, 0.3) * r)
            .abs()
            .max_element()
            < 1e-6
    );
    assert!(m[2].finish.layers.is_empty());
}

/// A square of `material` (glTF JSON) facing `n`, seen face on from +z
/// through a parallel view, lit by one white directional light from unit
/// direction `l` without ambient, with no environment: the colours of its
/// samples as the renderer draws them (linear, 0–1).
fn square(n: Vec3, l: Vec3, material: &str) -> Vec<[f64; 3]> {
    let (t, b) = n.any_orthonormal_pair();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(u, v)| t * u * 0.5 + b * v * 0.5);
    let mut d = common::Doc::default();
    let pos = d.vec3(&corners.map(|c| c.to_array()));
    let normal = d.vec3(&[n.to_array(); 4]);
    let idx = if t.cross(b).z > 0.0 {
        d.indices(&[[0, 1, 2], [0, 2, 3]])
    } else {
        d.indices(&[[0, 2, 1], [0, 3, 2]])
    };
    let glb = d.glb(&format!(
        r#""materials":[{material}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{normal}}},"indices":{idx},"material":0}}]}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0"#
    ));
    let g = gltf::parse(&glb, None, "square.glb", &LoadOptions::default())
        .unwrap()
        .geometry;
    let mut scene = Scene::builder()
        .camera(Camera {
            projection: Projection::Orthographic {
                height: 2.0,
                near: 0.1,
                far: 20.0,
            },
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        })
        .mesh(Mesh::of(Arc::new(g), Rgb::WHITE))
        .light(rastty::scene::Light {
            direction: -l,
            color: Rgb::WHITE,
            ambient: 0.0,
            ..Default::default()
        })
        .build()
        .unwrap();
    scene.environment = Environment::None;
    let c = common::colours(&scene, 20, 10);
    assert!(
        !c.is_empty() && c.len() <= 4,
        "the square drawn, nearly one colour: {c:?}"
    );
    c.iter()
        .map(|l| l.0.map(|x| f64::from(x) / 65535.0))
        .collect()
}

/// The GGX lobe of glTF's spec (Trowbridge-Reitz, Smith's height-correlated
/// visibility, Schlick's Fresnel of `f0`) times π and `n·l`.
fn ggx(n: DVec3, l: DVec3, v: DVec3, f0: f64, roughness: f64) -> f64 {
    let a2 = roughness.powi(4);
    let h = (l + v).normalize();
    let (nl, nv, nh, vh) = (n.dot(l), n.dot(v), n.dot(h), v.dot(h));
    let d = a2 / (std::f64::consts::PI * (nh * nh * (a2 - 1.0) + 1.0).powi(2));
    let vis =
        0.5 / (nl * (nv * nv * (1.0 - a2) + a2).sqrt() + nv * (nl * nl * (1.0 - a2) + a2).sqrt());
    let f = f0 + (1.0 - f0) * (1.0 - vh).powi(5);
    std::f64::consts::PI * d * vis * f * nl
}

/// The sheen lobe of glTF's spec (the Charlie distribution, Estevez and
/// Kulla's visibility) times π and `n·l`, for a white sheen.
fn charlie(n: DVec3, l: DVec3, v: DVec3, roughness: f64) -> f64 {
    let alpha = roughness * roughness;
    let h = (l + v).normalize();
    let (nl, nv, nh) = (n.dot(l), n.dot(v), n.dot(h));
    let sin = (1.0 - nh * nh).sqrt();
    let d = (2.0 + 1.0 / alpha) * sin.powf(1.0 / alpha) / (2.0 * std::f64::consts::PI);
    let t = (1.0 - alpha).powi(2);
    let mix = |a: f64, b: f64| a * (1.0 - t) + b * t;
    let l_fit = |x: f64| {
        mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * x.powf(mix(0.19823, 0.16801)))
            + mix(-1.97760, -1.27393) * x
            + mix(-4.32054, -4.85967)
    };
    let lambda = |c: f64| {
        if c < 0.5 {
            l_fit(c).exp()
        } else {
            (2.0 * l_fit(0.5) - l_fit(1.0 - c)).exp()
        }
    };
    let vis = (1.0 / ((1.0 + lambda(nv) + lambda(nl)) * 4.0 * nv * nl)).clamp(0.0, 1.0);
    std::f64::consts::PI * d * vis * nl
}

/// Whether every colour of `got` is `want` within the renderer's
/// rounding (f32 arithmetic, 16-bit channels).
fn near(got: &[[f64; 3]], want: [f64; 3]) -> bool {
    got.iter()
        .all(|c| (0..3).all(|i| (c[i] - want[i]).abs() <= 2e-4 + 1e-4 * want[i]))
}

/// Normals and light directions the squares are drawn at (the eye on +z).
fn angles() -> Vec<(Vec3, Vec3)> {
    vec![
        (Vec3::Z, Vec3::new(0.3, 0.2, 0.9)),
        (Vec3::new(0.5, 0.1, 0.8), Vec3::new(-0.2, 0.3, 0.9)),
        (Vec3::new(0.0, -0.6, 0.8), Vec3::new(0.7, 0.0, 0.7)),
        (Vec3::new(-0.8, 0.3, 0.5), Vec3::new(-0.1, 0.8, 0.6)),
    ]
}

#[test]
fn a_clear_coat_is_the_specs_lobe_over_what_it_dims() {
    for (n, l) in angles() {
        let (n, l) = (n.normalize(), l.normalize());
        let (dn, dl, dv) = (n.as_dvec3(), l.as_dvec3(), DVec3::Z);
        for (factor, roughness) in [(1.0f64, 0.1f64), (0.5, 0.5), (0.8, 0.9)] {
            let coat = ggx(dn, dl, dv, 0.04, roughness);
            let fresnel = 0.04 + 0.96 * (1.0 - dn.dot(dv)).powi(5);
            let keep = 1.0 - factor * fresnel;
            // Over black (a matte surface of no colour): the coat alone.
            let ext = format!(
                r#""extensions":{{"KHR_materials_clearcoat":{{"clearcoatFactor":{factor},"clearcoatRoughnessFactor":{roughness}}}}}"#
            );
            let black =
                format!(r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[0,0,0,1]}},{ext}}}"#);
            let got = square(n, l, &black);
            assert!(
                near(&got, [factor * coat; 3]),
                "{n} {l} {factor} {roughness}: {got:?} against {}",
                factor * coat
            );
            // Over a white matte: Lambert's n·l, dimmed by the coat's
            // Fresnel at n·v, and the coat.
            let white =
                format!(r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[1,1,1,1]}},{ext}}}"#);
            let want = dn.dot(dl) * keep + factor * coat;
            let got = square(n, l, &white);
            assert!(
                near(&got, [want; 3]),
                "{n} {l} {factor} {roughness}: {got:?} against {want}"
            );
        }
    }
}

#[test]
fn sheen_is_the_specs_lobe_in_its_colour_over_what_its_albedo_dims() {
    let color = [1.0, 0.5, 0.25];
    for (n, l) in angles() {
        let (n, l) = (n.normalize(), l.normalize());
        let (dn, dl, dv) = (n.as_dvec3(), l.as_dvec3(), DVec3::Z);
        for roughness in [0.3f64, 0.6, 1.0] {
            let lobe = charlie(dn, dl, dv, roughness);
            let ext = format!(
                r#""extensions":{{"KHR_materials_sheen":{{"sheenColorFactor":{color:?},"sheenRoughnessFactor":{roughness}}}}}"#
            );
            let black =
                format!(r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[0,0,0,1]}},{ext}}}"#);
            let got = square(n, l, &black);
            let want = color.map(|c| c * lobe);
            assert!(
                near(&got, want),
                "{n} {l} {roughness}: {got:?} against {want:?}"
            );
            // Over a white matte, dimmed by the sheen's albedo at n·v (the
            // renderer's table is within 0.01 of the integral).
            let white =
                format!(r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[1,1,1,1]}},{ext}}}"#);
            let e = rastty::sheen_albedo_reference(dn.dot(dv), roughness, 24);
            let got = square(n, l, &white);
            for c in &got {
                for i in 0..3 {
                    let want = dn.dot(dl) * (1.0 - e) + color[i] * lobe;
                    assert!(
                        (c[i] - want).abs() <= 0.01 * dn.dot(dl) + 3e-4,
                        "{n} {l} {roughness}: {c:?} against {want}"
                    );
                }
            }
        }
    }
}

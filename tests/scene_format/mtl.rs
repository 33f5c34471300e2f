//! OBJ files' MTL materials through a TOML scene: mapped onto embray's materials, warned
//! about with the MTL file and line, and rendered as their statements say.

use super::*;
use crate::common::command::{TempDir, temp_dir};
use crate::common::{options, render_ok};

/// Four unit-wide quads side by side at z = 0 (facing +z), one per material, left to right.
const QUADS: &str = "mtllib four.mtl
v -2 -0.5 0\nv -1 -0.5 0\nv -1 0.5 0\nv -2 0.5 0
v -1 -0.5 0\nv 0 -0.5 0\nv 0 0.5 0\nv -1 0.5 0
v 0 -0.5 0\nv 1 -0.5 0\nv 1 0.5 0\nv 0 0.5 0
v 1 -0.5 0\nv 2 -0.5 0\nv 2 0.5 0\nv 1 0.5 0
o matte\nusemtl matte\nf 1 2 3 4
o hole\nusemtl hole\nf 5 6 7 8
o glass\nusemtl glass\nf 9 10 11 12
o mirror\nusemtl mirror\nf 13 14 15 16
";

/// As exported, with the statements of a real exporter (Ka, Tf) beside the ones that count.
const FOUR_MTL: &str = "# four materials
newmtl matte
Ka 0.2 0.2 0.2
Kd 0.5 0.5 0.5
illum 1

newmtl hole
Kd 0.5 0.5 0.5
d 0

newmtl glass
Kd 0 0 0
Ks 1 1 1
Ni 1.5
Tf 1 1 1
illum 7

newmtl mirror
Kd 0 0 0
Ks 1 1 1
illum 3
";

/// The quads seen face on by a camera at z = 4, lit from the camera by a point light, in
/// front of a light behind them that faces the camera.
const SCENE: &str = r#"
[camera]
lookfrom = [0.0, 0.0, 4.0]
lookat = [0.0, 0.0, 0.0]
vfov = 14.0
resolution = [32, 8]

[[objects]]
type = "mesh"
file = "four.obj"

[[lights]]
type = "point"
position = [0.0, 0.0, 4.0]
intensity = [4.0, 4.0, 4.0]

[[lights]]
type = "quad"
corner = [-4.0, -2.0, -1.0]
u = [8.0, 0.0, 0.0]
v = [0.0, 4.0, 0.0]
emission = [1.0, 1.0, 1.0]
"#;

fn four_quads(name: &str) -> TempDir {
    let dir = temp_dir(name);
    std::fs::write(dir.join("four.obj"), QUADS).unwrap();
    std::fs::write(dir.join("four.mtl"), FOUR_MTL).unwrap();
    dir
}

#[test]
fn mtl_statements_become_materials_and_the_rest_warnings_with_lines() {
    let dir = four_quads("mtl-load");
    let (scene, warnings) = scene::load_str_with_warnings(SCENE, &dir.join("scene.toml")).unwrap();
    // The four quads (the light behind them is an object too).
    let kinds: Vec<Specular> =
        scene.objects[..4].iter().map(|o| scene.materials[o.material as usize].specular).collect();
    assert_eq!(
        kinds,
        [
            Specular::None,
            Specular::None,
            Specular::dielectric(1.5, Vec3::ZERO),
            Specular::Mirror { reflectance: Vec3::ONE },
        ]
    );
    let hole = material(&scene, "four.obj: hole");
    assert_eq!(hole.opacity, Some(embray::scene::Opacity::Constant(0.0)));
    let mtl = dir.join("four.mtl");
    assert_eq!(
        warnings,
        [format!(
            "{}: Ka (an ambient colour) is not used (material 'matte', line 3)",
            mtl.display()
        )]
    );
    // A scene that gives the object its own material reads no MTL statement.
    let own = SCENE.replace("file = \"four.obj\"", "file = \"four.obj\"\nmaterial = \"white\"");
    let own = format!("{own}\n{}", common::scene_files::WHITE);
    let (_, warnings) = scene::load_str_with_warnings(&own, &dir.join("scene.toml")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    std::fs::write(dir.join("four.mtl"), FOUR_MTL.replace("Ni 1.5", "Ni 0")).unwrap();
    let err = scene::load_str(SCENE, &dir.join("scene.toml")).unwrap_err().to_string();
    assert!(
        err.contains("four.mtl: material 'glass': Ni is 0, but glass needs Ni > 0 (line 14)"),
        "{err}"
    );
}

#[test]
fn a_hole_shows_the_light_behind_glass_refracts_it_and_a_mirror_the_dark_in_front() {
    let dir = four_quads("mtl-render");
    let scene = scene::load_str(SCENE, &dir.join("scene.toml")).unwrap();
    let film =
        render_ok(&scene, &options(&scene, embray::accel::BackendKind::default_compiled(), 16))
            .film;
    // The mean of the middle of each quad (8 columns each).
    let mean = |quad: u32| {
        let pixels: Vec<Vec3> = (2..6)
            .flat_map(|y| (8 * quad + 2..8 * quad + 6).map(move |x| (x, y)))
            .map(|(x, y)| film.pixel(x, y))
            .collect();
        pixels.iter().map(|c| c.element_sum() / 3.0).sum::<f32>() / pixels.len() as f32
    };
    let [matte, hole, glass, mirror] = [0, 1, 2, 3].map(mean);
    // Through the hole, the light behind (radiance 1) as it is.
    assert!((hole - 1.0).abs() < 0.02, "hole {hole}");
    // Glass of Ni 1.5 passes what its Fresnel reflection (4 % face on) does not take; one
    // glass surface has the light on its inside, whose radiance reaches the camera divided
    // by Ni².
    let through = (1.0 - 0.04) / (1.5 * 1.5);
    assert!((glass - through).abs() < 0.02, "glass {glass}, expected {through}");
    // The matte quad shows only the point light's light: 0.5/π · I cos θ / r² at its
    // centre (x = −1.5).
    let r2 = 4.0f32 * 4.0 + 1.5 * 1.5;
    let lit = 0.5 / std::f32::consts::PI * 4.0 * (4.0 / r2.sqrt()) / r2;
    assert!((matte - lit).abs() < 0.1 * lit, "matte {matte}, expected {lit}");
    // The mirror sees the dark in front of it (the point light is not seen in a mirror).
    assert!(mirror < 0.2 * matte, "mirror {mirror}, matte {matte}");
}

/// A missing library adds nothing to tobj's list of materials: the libraries after it still
/// give their materials to the models that name them.
#[test]
fn a_missing_library_leaves_the_others_materials_in_place() {
    let dir = four_quads("mtl-missing");
    let obj = QUADS.replace("mtllib four.mtl", "mtllib gone.mtl\nmtllib four.mtl");
    std::fs::write(dir.join("four.obj"), obj).unwrap();
    let (scene, warnings) = scene::load_str_with_warnings(SCENE, &dir.join("scene.toml")).unwrap();
    let names: Vec<&str> = scene.objects[..4]
        .iter()
        .map(|o| scene.materials[o.material as usize].name.as_str())
        .collect();
    assert_eq!(names, ["four.obj: matte", "four.obj: hole", "four.obj: glass", "four.obj: mirror"]);
    assert!(warnings.iter().any(|w| w.contains("gone.mtl")), "{warnings:?}");
}

//! Mitsuba's glass beyond the plain dielectric: tinted reflection and transmission, the
//! thin sheet (`thindielectric`), and `null`, as the reader turns them into materials and
//! `convert` writes them to TOML (their images: `glass_tints` and `null_bsdf` in `suite`).

use super::bsdfs::material_of;
use super::load_mitsuba;
use super::reader::{SENSOR, files};
use embray::scene::{MaterialDesc, Opacity, Specular};
use glam::Vec3;

#[test]
fn glass_tints_and_the_thin_sheet_are_read_with_mitsubas_defaults() {
    let thin = material_of("m-thin", "<bsdf type=\"thindielectric\"/>").unwrap();
    let bk7 = 1.5046 / 1.000277; // BK7 in air, as Mitsuba names them
    let Specular::ThinDielectric { ior, reflectance, transmittance } = thin.specular else {
        panic!("{:?}", thin.specular)
    };
    assert!((ior - bk7).abs() < 1e-4 && reflectance == Vec3::ONE && transmittance == Vec3::ONE);
    assert!(!thin.one_sided && thin.albedo == Vec3::ZERO);
    let tinted = material_of(
        "m-tinted",
        "<bsdf type=\"roughdielectric\"><float name=\"int_ior\" value=\"1.33\"/>\
         <float name=\"ext_ior\" value=\"1\"/>\
         <rgb name=\"specular_reflectance\" value=\"0.5\"/>\
         <rgb name=\"specular_transmittance\" value=\"0.2, 0.4, 0.6\"/></bsdf>",
    )
    .unwrap();
    let expected = Specular::Dielectric {
        ior: 1.33,
        absorption: Vec3::ZERO,
        reflectance: Vec3::splat(0.5),
        transmittance: Vec3::new(0.2, 0.4, 0.6),
    };
    assert_eq!(tinted.specular, expected);
    assert_eq!(tinted.roughness, 0.1);
    let null = material_of("m-null", "<bsdf type=\"null\"/>").unwrap();
    assert_eq!(null.opacity, Some(Opacity::Constant(0.0)));
    assert!(!null.one_sided);
}

#[test]
fn what_is_not_modelled_or_mitsuba_refuses_is_refused() {
    let cases = [
        (
            "<bsdf type=\"thindielectric\"><texture type=\"checkerboard\" \
             name=\"specular_transmittance\"/></bsdf>",
            "a textured `specular_transmittance` is not supported",
        ),
        (
            "<bsdf type=\"twosided\"><bsdf type=\"thindielectric\"/></bsdf>",
            "twosided cannot hold a transmitting BSDF",
        ),
        ("<bsdf type=\"twosided\"><bsdf type=\"null\"/></bsdf>", "twosided cannot hold"),
        (
            "<bsdf type=\"null\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf>",
            "does not take `reflectance`",
        ),
        (
            "<bsdf type=\"dielectric\"><rgb name=\"specular_reflectance\" value=\"1.5\"/></bsdf>",
            "a reflectance must be in [0, 1]",
        ),
    ];
    for (i, (bsdf, expected)) in cases.iter().enumerate() {
        let err = material_of(&format!("m-glass-refused-{i}"), bsdf).unwrap_err();
        assert!(err.contains(expected), "{bsdf}: {err}");
    }
}

/// The materials `embray convert` writes read back the same.
#[test]
fn tinted_glass_thin_sheets_and_null_convert_to_toml_and_back() {
    let bsdfs = [
        "<bsdf type=\"thindielectric\"><float name=\"int_ior\" value=\"1.7\"/>\
         <rgb name=\"specular_reflectance\" value=\"0.8\"/>\
         <rgb name=\"specular_transmittance\" value=\"0.9, 0.6, 0.4\"/></bsdf>",
        "<bsdf type=\"dielectric\"><rgb name=\"specular_transmittance\" value=\"0.5, 0.9, 0.7\"/>\
         </bsdf>",
        "<bsdf type=\"null\"/>",
    ];
    let shapes: String =
        bsdfs.iter().map(|b| format!("<shape type=\"cube\">{b}</shape>")).collect();
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n{shapes}\n</scene>"
    );
    let path = files("m-glass-convert", &main, &[]);
    let scene = load_mitsuba(&path, &[]).unwrap();
    let back = super::converted(&path, &scene);
    let scattering = |s: &embray::scene::SceneDesc| -> Vec<(Specular, Option<Opacity>, bool)> {
        let material = |i: usize| -> &MaterialDesc { &s.materials[s.objects[i].material as usize] };
        (0..3)
            .map(|i| (material(i).specular, material(i).opacity.clone(), material(i).one_sided))
            .collect()
    };
    assert_eq!(scattering(&back), scattering(&scene));
}

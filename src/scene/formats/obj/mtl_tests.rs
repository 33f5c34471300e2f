//! The MTL mapping: each statement's fields, the notes with their lines, bad values.

use super::mtl::{ObjMaterial, material_desc, newmtl_lines};
use super::mtl_mapping::coating_ior;
use super::mtl_notes::MtlNotes;
use super::{ObjRef, mtl_material::statements};
use crate::scene::desc::{BumpScale, Distribution, MaterialDesc, Opacity, Pattern, Specular};
use crate::scene::error::Line;
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn obj_ref() -> ObjRef<'static> {
    ObjRef {
        obj: PathBuf::from("m.obj"),
        scene: Path::new("s.toml"),
        item: "objects[0]".into(),
        line: Line(Some(4)),
        read_mtl: true,
    }
}

/// Material `m` of `dir/m.mtl`, whose block (after `newmtl m` on line 1) is `block`.
fn mapped_in(dir: &Path, block: &str) -> Result<(MaterialDesc, Vec<String>), String> {
    let m = ObjMaterial {
        name: "m".into(),
        mtl: dir.join("m.mtl"),
        text: Arc::from(format!("newmtl m\n{block}\nnewmtl other\nKs 1 0 0\n")),
        line: 1,
        offset: 0,
    };
    let mut notes = MtlNotes::default();
    let material = material_desc(&m, &obj_ref(), &mut notes).map_err(|e| e.to_string())?;
    let mut warnings = Vec::new();
    notes.flush(&mut warnings);
    Ok((material, warnings))
}

fn mapped(block: &str) -> (MaterialDesc, Vec<String>) {
    mapped_in(Path::new("dir"), block).unwrap()
}

fn error(block: &str) -> String {
    mapped_in(Path::new("dir"), block).unwrap_err()
}

#[track_caller]
fn assert_close(a: f32, b: f32) {
    assert!((a - b).abs() < 1e-6, "{a} != {b}");
}

/// The warnings name the MTL file, the material and each line.
#[track_caller]
fn assert_notes(warnings: &[String], expected: &[(&str, usize)]) {
    assert_eq!(warnings.len(), expected.len(), "{warnings:#?}");
    for (warning, (part, line)) in warnings.iter().zip(expected) {
        let place = format!("material 'm', line {line})");
        let file = warning.split(": ").next().unwrap();
        assert!(Path::new(file).ends_with("m.mtl"), "{warning}");
        assert!(warning.contains(part) && warning.ends_with(&place), "{warning}: {part}, {place}");
    }
}

#[test]
fn blocks_end_at_the_next_material() {
    let text = "# lib\nnewmtl a\nKd 1 1 1\n  # note\n\nnewmtl b c\n  Ks 0 0 0\n";
    assert_eq!(newmtl_lines(text), [(2, 6), (6, 34)]);
    assert!(text[34..].starts_with("newmtl b"));
    let a: Vec<_> = statements(text, 2, 6).iter().map(|s| (s.keyword, s.value, s.line)).collect();
    assert_eq!(a, [("Kd", "1 1 1", 3)]);
    assert_eq!(statements(text, 6, 34)[0].line, 7);
    // Line breaks of either kind.
    let crlf = text.replace('\n', "\r\n");
    let lines = newmtl_lines(&crlf);
    assert_eq!(lines, [(2, 7), (6, 39)]);
    let (line, offset) = lines[1];
    assert_eq!(statements(&crlf, line, offset)[0].line, 7);
}

#[test]
fn kd_and_ke_alone_give_the_lambertian_material_of_before() {
    let (m, warnings) = mapped("Kd 0.5 0.25 0\nKe 2 3 4\nNs 10\nNi 1.45\nd 1\nillum 1\nTf 1 1 1");
    let expected = MaterialDesc {
        albedo: Vec3::new(0.5, 0.25, 0.0),
        emission: Vec3::new(2.0, 3.0, 4.0),
        ..Default::default()
    };
    assert_eq!((m, warnings), (expected, vec![]));
    assert_eq!(mapped("").0, MaterialDesc::default());
    // Sponza: illum 2 with a black Ks has no highlight.
    assert_eq!(mapped("illum 2\nKs 0 0 0").0.specular, Specular::None);
}

#[test]
fn a_highlight_is_a_plastic_coating_as_strong_as_ks_and_as_rough_as_ns() {
    for illum in ["illum 2\n", ""] {
        let (m, warnings) = mapped(&format!("{illum}Kd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 98"));
        assert!(warnings.is_empty(), "{warnings:?}");
        let Specular::Plastic { ior, nonlinear: false } = m.specular else { panic!("{m:?}") };
        assert_close(ior, 1.5);
        assert_close(m.roughness, 0.02f32.sqrt());
        assert_eq!((m.distribution, m.albedo), (Distribution::Beckmann, Vec3::new(0.8, 0.1, 0.1)));
    }
    // Without Ns, and from the top of Ns's range: smooth.
    assert_eq!(mapped("Ks 1 1 1").0.roughness, 0.0);
    assert_eq!(mapped("Ks 1 1 1\nNs 1000").0.roughness, 0.0);
    assert_close(mapped("Ks 1 1 1\nNs 0").0.roughness, 1.0);
    assert_close(coating_ior(1.0), (1.0 + 0.08f32.sqrt()) / (1.0 - 0.08f32.sqrt()));
    // A tinted Ks: the coating is as strong as its mean.
    let (m, warnings) = mapped("Ks 0.9 0.6 0.0\nillum 2");
    assert_eq!(m.specular, Specular::Plastic { ior: coating_ior(0.5), nonlinear: false });
    assert_notes(&warnings, &[("Ks's tint is not modelled", 2)]);
}

#[test]
fn illum_chooses_the_lobe() {
    let (m, warnings) = mapped("Kd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nillum 1");
    assert_eq!((m.specular, m.roughness), (Specular::None, 0.0));
    assert_notes(&warnings, &[("Ks is not used: illum 1 has no specular highlight", 3)]);
    let (m, warnings) = mapped("illum 0");
    assert_eq!(m.specular, Specular::None);
    assert_notes(&warnings, &[("illum 0 (a constant colour, unlit)", 2)]);

    let (m, warnings) = mapped("Kd 0.2 0.3 0.4\nKs 0.7 0.6 0.5\nNs 48\nillum 3");
    assert_eq!(m.specular, Specular::Mirror { reflectance: Vec3::new(0.7, 0.6, 0.5) });
    assert_eq!(m.albedo, Vec3::new(0.2, 0.3, 0.4));
    assert_close(m.roughness, 0.2);
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_notes(&mapped("Ks 1 1 1\nillum 5").1, &[("Fresnel reflection is not modelled", 3)]);

    for illum in [4, 6, 7, 9] {
        let (m, warnings) = mapped(&format!("Kd 0 0 0\nKs 1 1 1\nNi 1.33\nillum {illum}"));
        assert_eq!(m.specular, Specular::dielectric(1.33, Vec3::ZERO));
        assert!(warnings.is_empty(), "{warnings:?}");
    }
    let (m, warnings) = mapped("Kd 0.8 0.8 0.8\nillum 7\nNs 1000");
    assert_eq!(m.specular, Specular::dielectric(1.5, Vec3::ZERO));
    assert_eq!(m.roughness, 0.0);
    assert_notes(&warnings, &[("Kd is not used: glass has no diffuse part", 2)]);
    assert_notes(&mapped("illum 12").1, &[("illum 12 is not one of MTL's models", 2)]);
}

#[test]
fn pbr_roughness_and_metallic_are_read() {
    // A principled dielectric has a specular layer without Ks (Blender's level 0.5).
    let (m, warnings) = mapped("Kd 0.5 0.5 0.5\nPr 0.5\nNs 10");
    assert_eq!(m.specular, Specular::Plastic { ior: coating_ior(0.5), nonlinear: false });
    assert_eq!((m.roughness, m.distribution), (0.25, Distribution::Ggx));
    assert!(warnings.is_empty());
    let (m, _) = mapped("Kd 0.9 0.6 0.2\nPm 1\nPr 0.1\nillum 2");
    assert_eq!(m.specular, Specular::Mirror { reflectance: Vec3::new(0.9, 0.6, 0.2) });
    assert_eq!(m.albedo, Vec3::ZERO);
    assert_close(m.roughness, 0.01);
    let (m, warnings) = mapped("Pm 0.25");
    assert!(matches!(m.specular, Specular::Plastic { .. }), "{m:?}");
    assert_notes(
        &warnings,
        &[("Pm between 0 and 1 (a partly metallic surface) is not modelled: read as 0", 2)],
    );
}

#[test]
fn dissolve_is_a_mask() {
    assert_eq!(mapped("d 0.25").0.opacity, Some(Opacity::Constant(0.25)));
    assert_eq!(mapped("Tr 0.25").0.opacity, Some(Opacity::Constant(0.75)));
    assert_eq!(mapped("d 1\nTr 0").0.opacity, None);
    let (m, warnings) = mapped("d 0.5\nTr 0.9");
    assert_eq!(m.opacity, Some(Opacity::Constant(0.5)));
    assert_notes(&warnings, &[("Tr is not 1 − d: d is used", 3)]);
    let (m, warnings) = mapped("Tr 1");
    assert_eq!(m.opacity, Some(Opacity::Constant(0.0)));
    assert_notes(&warnings, &[("Tr 1 (fully transparent) hides the surface", 2)]);
}

#[test]
fn what_is_not_used_is_noted_with_its_line() {
    let block = "Kd 0.5 0.5 0.5\nKa 0.2 0.2 0.2\nKa 0 0 0\nTf 0.5 1 1\nsharpness 60\n\
                 map_Ns shiny.png\nNi 0\nfoo 1\nKs 0 0 0 1\nmap_Ks spec.png\nKa 0.1 0.1 0.1";
    let (m, warnings) = mapped(block);
    assert_eq!(m.albedo, Vec3::splat(0.5));
    assert_notes(
        &warnings,
        &[
            // Both places in one warning: the message names no line.
            ("Ka is given again later, which is used (material 'm', line 3; ", 4),
            ("Tf (a transmission filter) is not modelled", 5),
            ("sharpness (the sharpness of reflection maps) is not supported", 6),
            ("map_Ns (a texture of the specular exponent) is not supported", 7),
            ("Ni is not an index of refraction (it must be > 0); only glass reads it", 8),
            ("'foo' is not an MTL statement embray knows", 9),
            ("Ks takes 3 value(s); the 1 after them are not used", 10),
            ("map_Ks (a texture of Ks) is not supported", 11),
            ("Ka (an ambient colour) is not used", 12),
        ],
    );
}

#[test]
fn statements_read_only_to_be_warned_about_are_never_errors() {
    let (m, warnings) = mapped("Tf spectral glass.rfl 1\nKa 1 nan 0");
    assert_eq!(m, MaterialDesc::default());
    assert_notes(
        &warnings,
        &[("Tf is not understood (3 numbers)", 2), ("Ka is not understood (3 numbers)", 3)],
    );
}

#[test]
fn bad_values_name_the_file_the_material_and_the_line() {
    let place = |line: usize| format!("(line {line}); named by objects[0] in 's.toml'");
    let cases = [
        ("Ns -3", "Ns is -3, but must be finite and >= 0"),
        ("d 2", "d is 2, but must be in [0, 1]"),
        ("Tr -0.5", "Tr is -0.5, but must be in [0, 1]"),
        ("Kd 0.5 1.5 0", "Kd[1] is 1.5, but must be in [0, 1]"),
        ("Ks 0 0 2", "Ks[2] is 2, but must be in [0, 1]"),
        ("Ke 0 -1 0", "Ke[1] is -1, but must be finite and >= 0"),
        ("Ke inf 0 0", "Ke[0] is inf, but must be finite and >= 0"),
        ("Pr 1.5", "Pr is 1.5, but must be in [0, 1]"),
        ("Ns nan", "Ns is NaN, but must be finite and >= 0"),
        ("kd 1 1", "kd needs 3 numbers"),
        ("illum two", "illum needs a whole number from 0 to 255"),
        ("Ni 0\nillum 6", "Ni is 0, but glass needs Ni > 0"),
        ("map_Kd -bm", "map_Kd gives -bm without its 1 value(s)"),
        ("bump -bm x h.png", "bump gives -bm 'x', not a finite number"),
        ("norm -s 2", "norm names no image file"),
    ];
    for (block, problem) in cases {
        let err = error(&format!("Kd 1 1 1\n{block}"));
        let mtl = Path::new("dir/m.mtl").display().to_string();
        assert!(err.starts_with(&format!("{mtl}: material 'm': {problem} {}", place(3))), "{err}");
    }
}

fn write_png(path: &Path, width: u32, texel: impl Fn(u32) -> [u8; 4]) {
    image::RgbaImage::from_fn(width, 1, |x, _| image::Rgba(texel(x))).save(path).unwrap();
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("embray-mtl-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The texels of an image texture, divided by its normalizer.
fn texels(t: &crate::scene::TextureDesc) -> Vec<Vec3> {
    let Pattern::Image { image, normalizer, .. } = &t.pattern else { panic!("{t:?}") };
    image.texels.iter().map(|c| *c / *normalizer).collect()
}

#[test]
fn maps_become_textures_of_their_fields() {
    let dir = temp_dir("maps");
    write_png(&dir.join("mask.png"), 2, |x| [200, 10, 10, [255, 0][x as usize]]);
    write_png(&dir.join("height.png"), 2, |x| {
        let v = [0, 255][x as usize];
        [v, v, v, 255]
    });
    write_png(&dir.join("normals.png"), 2, |x| [[120, 136][x as usize], 128, 250, 255]);
    write_png(&dir.join("glow.png"), 2, |x| [[255, 0][x as usize], 0, 0, 255]);
    let block = "map_d -imfchan m mask.png\nbump -bm 0.02 height.png\nmap_Ke glow.png\nKe 2 2 2";
    let (m, warnings) = mapped_in(&dir, block).unwrap();
    let Some(Opacity::Texture(mask)) = &m.opacity else { panic!("{:?}", m.opacity) };
    assert_eq!(texels(mask), [Vec3::ONE, Vec3::ZERO], "the alpha, not the colour");
    let bump = m.bump_map.as_ref().unwrap();
    assert_eq!((bump.factor, bump.scale), (0.02, BumpScale::Scene));
    assert_eq!(texels(&bump.texture), [Vec3::ZERO, Vec3::ONE]);
    // The image (sRGB decoded) times Ke.
    assert_eq!(m.emission, Vec3::splat(2.0));
    assert_eq!(texels(m.emission_texture.as_ref().unwrap()), [Vec3::X, Vec3::ZERO]);
    assert_notes(&warnings, &[("map_d options '-imfchan m' are not supported", 2)]);
    // Exporters' normal maps given as bump maps are normal maps; `norm` is one.
    let (m, warnings) = mapped_in(&dir, "map_Bump normals.png").unwrap();
    assert!(m.bump_map.is_none());
    assert_eq!(texels(m.normal_map.as_ref().unwrap())[0], Vec3::new(120.0, 128.0, 250.0) / 255.0);
    assert_notes(&warnings, &[("map_Bump's image looks like a tangent-space normal map", 2)]);
    let (m, warnings) = mapped_in(&dir, "norm normals.png\nbump height.png").unwrap();
    assert!(m.normal_map.is_some() && m.bump_map.is_none());
    assert_notes(&warnings, &[("bump is not used: norm gives the normal map", 3)]);
    // Glass has no diffuse part to paint: the image is not even read.
    let (m, warnings) = mapped_in(&dir, "illum 6\nmap_Kd absent.png").unwrap();
    assert!(m.texture.is_none());
    assert_notes(&warnings, &[("map_Kd is not used: glass has no diffuse part", 3)]);
    let err = mapped_in(&dir, "map_d absent.png").unwrap_err();
    for part in ["absent.png", "m.mtl", "line 2", "map_d of material 'm'"] {
        assert!(err.contains(part), "'{part}' not in: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

//! Mitsuba's BSDFs as the reader turns them into materials: each family's defaults and
//! conventions (one-sided unless `twosided`, glass two-sided, Beckmann unless told, a mask's
//! opacity 0.5), and the refusals of what embray does not model.

use super::common::assert_contains;
use super::load_mitsuba;
use super::reader::{SENSOR, files};
use embray::scene::{Distribution, MaterialDesc, Opacity, Specular};
use glam::Vec3;

/// The material of the one cube of a scene whose cube has the BSDF `bsdf`.
pub(super) fn material_of(name: &str, bsdf: &str) -> Result<MaterialDesc, String> {
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n<shape type=\"cube\">{bsdf}</shape>\n</scene>"
    );
    let scene = load_mitsuba(&files(name, &main, &[]), &[])?;
    Ok(scene.materials[scene.objects[0].material as usize].clone())
}

#[test]
fn each_family_reads_with_mitsubas_defaults() {
    let rough = material_of("m-rc", "<bsdf type=\"roughconductor\"/>").unwrap();
    assert_eq!((rough.distribution, rough.roughness), (Distribution::Beckmann, 0.1));
    assert!(rough.one_sided, "Mitsuba's BSDFs are black from behind");
    assert_eq!(rough.specular, Specular::Mirror { reflectance: Vec3::ONE });

    let plastic = material_of("m-pl", "<bsdf type=\"plastic\"/>").unwrap();
    let Specular::Plastic { ior, nonlinear } = plastic.specular else { panic!("{plastic:?}") };
    // Polypropylene over air, Mitsuba's default coating; a base of 0.5.
    assert!((ior - 1.49 / 1.000277).abs() < 1e-6 && !nonlinear);
    assert_eq!((plastic.albedo, plastic.roughness), (Vec3::splat(0.5), 0.0));

    let rough_plastic = material_of(
        "m-rpl",
        "<bsdf type=\"roughplastic\"><string name=\"distribution\" value=\"ggx\"/>\
         <float name=\"alpha\" value=\"0.3\"/><boolean name=\"nonlinear\" value=\"true\"/>\
         <rgb name=\"diffuse_reflectance\" value=\"0.1, 0.2, 0.3\"/></bsdf>",
    )
    .unwrap();
    assert_eq!(rough_plastic.distribution, Distribution::Ggx);
    assert_eq!(rough_plastic.roughness, 0.3);
    assert!(matches!(rough_plastic.specular, Specular::Plastic { nonlinear: true, .. }));
    assert_eq!(rough_plastic.albedo, Vec3::new(0.1, 0.2, 0.3));

    let glass = material_of(
        "m-rd",
        "<bsdf type=\"roughdielectric\"><float name=\"alpha\" value=\"0.2\"/>\
         <string name=\"int_ior\" value=\"water\"/></bsdf>",
    )
    .unwrap();
    let Specular::Dielectric { ior, .. } = glass.specular else { panic!("{glass:?}") };
    assert!((ior - 1.333 / 1.000277).abs() < 1e-6, "{ior}");
    assert_eq!((glass.distribution, glass.roughness), (Distribution::Beckmann, 0.2));
    assert!(!glass.one_sided, "glass is seen from both sides");
    // `sample_visible` only chooses how directions are drawn: the same material.
    let drawn_otherwise = material_of(
        "m-rd-sv",
        "<bsdf type=\"roughdielectric\"><float name=\"alpha\" value=\"0.2\"/>\
         <string name=\"int_ior\" value=\"water\"/>\
         <boolean name=\"sample_visible\" value=\"false\"/></bsdf>",
    )
    .unwrap();
    assert_eq!(drawn_otherwise, glass);

    let masked = material_of(
        "m-mask",
        "<bsdf type=\"mask\"><bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></bsdf>",
    )
    .unwrap();
    assert_eq!(masked.opacity, Some(Opacity::Constant(0.5)));
    assert!(!masked.one_sided);
    assert_eq!(masked.albedo, Vec3::splat(0.5));
}

#[test]
fn what_is_not_modelled_is_refused_by_name_and_line() {
    let cases = [
        (
            "<bsdf type=\"roughplastic\"><float name=\"alpha_u\" value=\"0.1\"/>\
             <float name=\"alpha_v\" value=\"0.3\"/></bsdf>",
            "roughplastic takes one alpha",
        ),
        (
            "<bsdf type=\"roughconductor\"><float name=\"alpha_u\" value=\"0.1\"/></bsdf>",
            "alpha_u and alpha_v are given together",
        ),
        (
            "<bsdf type=\"roughplastic\"><string name=\"distribution\" value=\"phong\"/></bsdf>",
            "the distribution 'phong' is not known",
        ),
        (
            "<bsdf type=\"mask\"><bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf></bsdf>",
            "a mask inside a mask is not supported",
        ),
        (
            "<bsdf type=\"mask\"><float name=\"opacity\" value=\"1.5\"/><bsdf type=\"diffuse\"/></bsdf>",
            "opacity is 1.5, but must be in [0, 1]",
        ),
        (
            "<bsdf type=\"plastic\"><rgb name=\"specular_reflectance\" value=\"0.5\"/></bsdf>",
            "specular_reflectance other than 1 is not supported",
        ),
        (
            "<bsdf type=\"roughdielectric\"><string name=\"sample_visible\" value=\"no\"/></bsdf>",
            "sample_visible",
        ),
        (
            "<bsdf type=\"plastic\"><float name=\"int_ior\" value=\"1.2\"/>\
             <float name=\"ext_ior\" value=\"1.2\"/></bsdf>",
            "must differ",
        ),
        (
            "<bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"mesh_attribute\">\
             <string name=\"name\" value=\"face_color\"/></texture></bsdf>",
            "looks up the mesh attribute `face_color`, which the shape does not have (it has: none)",
        ),
        (
            "<bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"checkerboard\">\
             <string name=\"wrap_mode\" value=\"clamp\"/></texture></bsdf>",
            "the checkerboard texture does not take `wrap_mode` (it takes: color0, color1, to_uv)",
        ),
        // Each was read past, leaving Mitsuba's default in its place.
        (
            "<bsdf type=\"conductor\"><string name=\"material\" value=\"Ag\"/>\
             <texture type=\"checkerboard\" name=\"specular_reflectance\"/></bsdf>",
            "a textured `specular_reflectance` is not supported in <bsdf type=\"conductor\">",
        ),
        (
            "<bsdf type=\"roughconductor\"><texture type=\"checkerboard\" name=\"distribution\"/></bsdf>",
            "`distribution` must be a <string>",
        ),
        (
            "<bsdf type=\"conductor\"><float name=\"material\" value=\"1\"/></bsdf>",
            "`material` must be a <string>",
        ),
        (
            "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/></bsdf>",
            "a different BSDF for the back is not supported",
        ),
        (
            "<bsdf type=\"bumpmap\"><texture type=\"checkerboard\"/>\
             <texture type=\"checkerboard\" name=\"b\"/><bsdf type=\"diffuse\"/></bsdf>",
            "bumpmap takes one height <texture>, not 2",
        ),
        (
            "<bsdf type=\"diffuse\"><texture type=\"checkerboard\" name=\"reflectance\">\
             <float name=\"to_uv\" value=\"2\"/></texture></bsdf>",
            "`to_uv` must be a <transform>",
        ),
        (
            "<bsdf type=\"dielectric\"><texture type=\"checkerboard\" name=\"int_ior\"/></bsdf>",
            "`int_ior` must be a <float> or a <string>",
        ),
    ];
    for (i, (bsdf, expected)) in cases.into_iter().enumerate() {
        let message = material_of(&format!("m-refused-{i}"), bsdf).unwrap_err();
        assert_contains(&message, &[expected, "main.xml", "(line 15)"]);
    }
}

/// A spectrum file (`.spd`, found through `<path>` as Mitsuba finds it) converts as the
/// same pairs given inline; a bad line is named with its file and line.
#[test]
fn a_spectrum_file_reads_as_its_pairs_inline() {
    let inline = material_of(
        "m-spd-inline",
        "<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"400:0.2, 550:0.6, 700:0.9\"/></bsdf>",
    )
    .unwrap();
    let main = format!(
        "<scene version=\"3.0.0\">\n<path value=\"data\"/><default name=\"spp\" value=\"1\"/>\
         <default name=\"fov\" value=\"40\"/>{SENSOR}\n<shape type=\"cube\"><bsdf type=\"diffuse\">\
         <spectrum name=\"reflectance\" filename=\"red.spd\"/></bsdf></shape>\n</scene>"
    );
    let spd = "# a reddish reflectance\n400 0.2\n550 0.6\n700 0.9\n";
    let scene = load_mitsuba(&files("m-spd-file", &main, &[("data/red.spd", spd)]), &[]).unwrap();
    let from_file = &scene.materials[scene.objects[0].material as usize];
    assert_eq!(from_file.albedo, inline.albedo);
    assert!(inline.albedo.x > inline.albedo.z, "{}", inline.albedo);
    let bad = main.replace("red.spd", "bad.spd");
    let path = files("m-spd-bad", &bad, &[("data/bad.spd", "400 0.2\n550 0.6 0.1\n")]);
    let message = load_mitsuba(&path, &[]).unwrap_err();
    assert_contains(&message, &["bad.spd, line 2: 3 numbers", "main.xml", "(line 15)"]);
}

/// `to_uv` other than a uniform scale maps the texture coordinates as Mitsuba's 2-D
/// transform does (applied in the order written: here shifted, then scaled).
#[test]
fn to_uv_maps_texture_coordinates() {
    let material = material_of(
        "m-to-uv",
        "<bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"checkerboard\">\
         <transform name=\"to_uv\"><translate x=\"0.5\"/><scale x=\"2\" y=\"3\"/></transform>\
         </texture></bsdf>",
    )
    .unwrap();
    let pattern = material.texture.unwrap().pattern;
    let embray::scene::Pattern::UvMapped(mapped) = pattern else { panic!("{pattern:?}") };
    let at = mapped.uv_from_surface.transform_point2(glam::Vec2::new(0.25, 0.5));
    assert_eq!(at, glam::Vec2::new(1.5, 1.5));
    assert_eq!(mapped.wrap, embray::scene::Wrap::Repeat);
}

/// A textured roughness (here α along ∂p/∂u a checkerboard, across it a number) is kept by
/// `embray convert`: TOML `roughness = [{ texture }, { texture }]`.
#[test]
fn a_textured_roughness_converts_to_toml_and_back() {
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n<shape type=\"cube\"><bsdf type=\"roughconductor\">\
         <texture name=\"alpha_u\" type=\"checkerboard\"><float name=\"color0\" value=\"0.05\"/>\
         <float name=\"color1\" value=\"0.4\"/></texture><float name=\"alpha_v\" value=\"0.2\"/>\
         </bsdf></shape>\n</scene>"
    );
    let path = files("m-rough-texture-convert", &main, &[]);
    let scene = load_mitsuba(&path, &[]).unwrap();
    let back = super::converted(&path, &scene);
    let textures = |s: &embray::scene::SceneDesc| {
        s.materials[s.objects[0].material as usize].roughness_textures.clone().expect("textured")
    };
    assert_eq!(textures(&back), textures(&scene));
}

/// A colour texture read as a number (here a mask's opacity) is its luminance, as Mitsuba's
/// `eval_1` reads it, on the squares `eval_1` puts each colour.
#[test]
fn a_colour_read_as_a_number_is_its_luminance() {
    let material = material_of(
        "m-luminance",
        "<bsdf type=\"mask\"><texture name=\"opacity\" type=\"checkerboard\">\
         <rgb name=\"color0\" value=\"1, 0, 0\"/><rgb name=\"color1\" value=\"0, 0, 1\"/>\
         </texture><bsdf type=\"diffuse\"/></bsdf>",
    )
    .unwrap();
    let Some(Opacity::Texture(texture)) = material.opacity else { panic!("{material:?}") };
    let embray::scene::Pattern::Checker2d { even, odd, .. } = texture.pattern else {
        panic!("{texture:?}")
    };
    assert_eq!((even, odd), (Vec3::splat(0.0722), Vec3::splat(0.2126)));
}

/// A `<float>` (or `<integer>`) where Mitsuba takes a colour is that constant grey, in every
/// BSDF's colour (it was ignored: the default was rendered).
#[test]
fn a_number_as_a_colour_is_a_grey() {
    let grey = |bsdf: &str| material_of("m-grey", bsdf).unwrap();
    let diffuse = grey("<bsdf type=\"diffuse\"><float name=\"reflectance\" value=\"0.1\"/></bsdf>");
    assert_eq!(diffuse.albedo, Vec3::splat(0.1));
    let plastic = grey(
        "<bsdf type=\"roughplastic\"><float name=\"diffuse_reflectance\" value=\"0.2\"/></bsdf>",
    );
    assert_eq!(plastic.albedo, Vec3::splat(0.2));
    let principled =
        grey("<bsdf type=\"principled\"><integer name=\"base_color\" value=\"1\"/></bsdf>");
    assert_eq!(principled.albedo, Vec3::ONE);
    let conductor = grey(
        "<bsdf type=\"conductor\"><float name=\"specular_reflectance\" value=\"0.3\"/></bsdf>",
    );
    assert_eq!(conductor.specular, Specular::Mirror { reflectance: Vec3::splat(0.3) });
    // Mitsuba's k defaults to 1 beside an eta (it was 0).
    let metal = grey("<bsdf type=\"conductor\"><float name=\"eta\" value=\"0.5\"/></bsdf>");
    let Specular::Conductor { eta, k, .. } = metal.specular else { panic!("{metal:?}") };
    assert_eq!((eta, k), (Vec3::splat(0.5), Vec3::ONE));
}

/// A wrapper takes its BSDF under any name, as Mitsuba does, also by reference: a
/// `<ref name="bsdf" id=…>` in a `twosided` is the BSDF it names, and a reference by another
/// name to what is no BSDF is refused.
#[test]
fn a_wrapper_takes_a_named_reference_to_its_bsdf() {
    let scene = |inner: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
             value=\"40\"/>{SENSOR}\n<bsdf type=\"diffuse\" id=\"white\"><rgb name=\"reflectance\" \
             value=\"0.8\"/></bsdf>\n<texture type=\"checkerboard\" id=\"board\"/>\n<shape \
             type=\"cube\"><bsdf type=\"twosided\">{inner}</bsdf></shape>\n</scene>"
        )
    };
    let load = |name: &str, inner: &str| load_mitsuba(&files(name, &scene(inner), &[]), &[]);
    let named = load("m-ref-named", "<ref name=\"bsdf\" id=\"white\"/>").unwrap();
    let material = &named.materials[named.objects[0].material as usize];
    assert_eq!(material.albedo, Vec3::splat(0.8));
    assert!(!material.one_sided);
    let wrong = load("m-ref-texture", "<ref name=\"bsdf\" id=\"board\"/>").unwrap_err();
    assert_contains(
        &wrong,
        &["<ref name=\"bsdf\" id=\"board\">", "is a <texture>, not a <bsdf>", "(line "],
    );
}

/// A bumpmap takes its height texture under any name or none, as Mitsuba does (an unnamed
/// one was refused), and by a reference without a name too.
#[test]
fn a_bumpmap_takes_its_texture_under_any_name_or_none() {
    let textures =
        ["<texture type=\"checkerboard\"/>", "<texture type=\"checkerboard\" name=\"h\"/>"];
    for (i, texture) in textures.into_iter().enumerate() {
        let bsdf = format!(
            "<bsdf type=\"bumpmap\">{texture}<float name=\"scale\" value=\"0.5\"/>\
             <bsdf type=\"roughplastic\"/></bsdf>"
        );
        let material = material_of(&format!("m-bump-{i}"), &bsdf).unwrap();
        assert_eq!(material.bump_map.as_ref().expect("a bump map").factor, 0.5);
        assert!(matches!(material.specular, Specular::Plastic { .. }), "{material:?}");
    }
    let main = format!(
        "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"1\"/><default name=\"fov\" \
         value=\"40\"/>{SENSOR}\n<texture type=\"checkerboard\" id=\"board\"/>\n<shape \
         type=\"cube\"><bsdf type=\"bumpmap\"><ref id=\"board\"/><bsdf type=\"diffuse\"/></bsdf>\
         </shape>\n</scene>"
    );
    let scene = load_mitsuba(&files("m-bump-ref", &main, &[]), &[]).unwrap();
    let material = &scene.materials[scene.objects[0].material as usize];
    assert!(material.bump_map.is_some(), "{material:?}");
}

/// A `<boolean>` is `true` or `false` in any case, as Mitsuba's parser compares them (`True`
/// was refused); nothing else is.
#[test]
fn a_boolean_is_read_in_any_case_and_nothing_more() {
    let plastic = |name: &str, value: &str| {
        material_of(
            name,
            &format!(
                "<bsdf type=\"plastic\"><boolean name=\"nonlinear\" value=\"{value}\"/></bsdf>"
            ),
        )
    };
    let upper = plastic("m-bool-true", "True").unwrap();
    assert!(matches!(upper.specular, Specular::Plastic { nonlinear: true, .. }));
    let lower = plastic("m-bool-false", "FALSE").unwrap();
    assert!(matches!(lower.specular, Specular::Plastic { nonlinear: false, .. }));
    for (i, value) in ["yes", "1", " true"].into_iter().enumerate() {
        let message = plastic(&format!("m-bool-bad-{i}"), value).unwrap_err();
        assert_contains(&message, &["is not true or false", "main.xml", "(line 15)"]);
    }
}

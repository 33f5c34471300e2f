//! Camera and render settings, material types, textures.

use super::*;

#[test]
fn f_number_and_focal_length_give_the_aperture() {
    let scene =
        load(&format!("{CAMERA}f_number = 2.0\nfocal_length = 0.05\nfocus_distance = 4.5\n"));
    assert_eq!(scene.camera.aperture, 0.025);
    assert_eq!(scene.camera.focus_distance, Some(4.5));
    assert_eq!(scene.camera.lens_shape, LensShape::Disk);
}

#[test]
fn aperture_and_lens_shape() {
    let scene = load(&format!("{CAMERA}aperture = 0.2\nlens = \"square\"\n"));
    assert_eq!((scene.camera.aperture, scene.camera.lens_shape), (0.2, LensShape::Square));
    let scene = load(&format!("{CAMERA}lens = \"disk\"\n"));
    assert_eq!((scene.camera.aperture, scene.camera.lens_shape), (0.0, LensShape::Disk));
}

#[test]
fn light_samples_and_integrator() {
    let scene = load(CAMERA);
    assert_eq!(scene.settings.light_samples, 1);
    assert_eq!(scene.settings.integrator, IntegratorKind::Path);
    let scene = load(&format!("{CAMERA}[render]\nlight_samples = 4\nintegrator = \"whitted\"\n"));
    assert_eq!(scene.settings.light_samples, 4);
    assert_eq!(scene.settings.integrator, IntegratorKind::Whitted);
    let scene = load(&format!("{CAMERA}[render]\nintegrator = \"path\"\n"));
    assert_eq!(scene.settings.integrator, IntegratorKind::Path);
}

const MATERIALS: &str = r#"
[materials.plain]

[materials.chrome]
type = "mirror"

[materials.tinted]
type = "mirror"
albedo = [0.1, 0.1, 0.1]
reflectance = [0.9, 0.8, 0.7]
roughness = 0.05
emission = [0.5, 0.0, 0.0]

[materials.metal]
type = "conductor"
eta = [0.2, 0.9, 1.1]
k = [3.9, 2.4, 2.1]
reflectance = [0.5, 0.5, 0.5]
roughness = 0.2

[materials.gold]
type = "conductor"
preset = "gold"

[materials.aluminum]
type = "conductor"
preset = "aluminum"

[materials.glass]
type = "dielectric"

[materials.green_glass]
type = "dielectric"
ior = 1.33
absorption = [0.5, 0.0, 0.5]
roughness = 0.1
"#;

#[test]
fn material_types_and_their_defaults() {
    let scene = load(&format!("{CAMERA}{MATERIALS}"));
    let plain = material(&scene, "plain");
    assert_eq!(*plain, MaterialDesc { name: "plain".to_owned(), ..MaterialDesc::default() });
    assert_eq!(plain.albedo, Vec3::splat(0.8));

    let chrome = material(&scene, "chrome");
    assert_eq!(chrome.albedo, Vec3::ZERO);
    assert_eq!(chrome.specular, Specular::Mirror { reflectance: Vec3::ONE });
    assert_eq!(chrome.roughness, 0.0);

    let tinted = material(&scene, "tinted");
    assert_eq!(tinted.albedo, Vec3::splat(0.1));
    assert_eq!(tinted.emission, Vec3::new(0.5, 0.0, 0.0));
    assert_eq!(tinted.specular, Specular::Mirror { reflectance: Vec3::new(0.9, 0.8, 0.7) });
    assert_eq!(tinted.roughness, 0.05);

    let metal = material(&scene, "metal");
    assert_eq!(
        metal.specular,
        Specular::Conductor {
            eta: Vec3::new(0.2, 0.9, 1.1),
            k: Vec3::new(3.9, 2.4, 2.1),
            reflectance: Vec3::splat(0.5)
        }
    );
    assert_eq!((metal.albedo, metal.roughness), (Vec3::ZERO, 0.2));

    let Specular::Conductor { eta, k, reflectance } = &material(&scene, "gold").specular else {
        panic!("gold is not a conductor");
    };
    assert!((*eta - Vec3::new(0.1431, 0.3750, 1.4425)).abs().max_element() < 1e-4, "{eta}");
    assert!((*k - Vec3::new(3.9832, 2.3857, 1.6032)).abs().max_element() < 1e-4, "{k}");
    assert_eq!(*reflectance, Vec3::ONE);
    let Specular::Conductor { eta, .. } = &material(&scene, "aluminum").specular else {
        panic!("aluminum is not a conductor");
    };
    assert!((eta.x - 1.6575).abs() < 1e-4, "{eta}");

    let glass = material(&scene, "glass");
    assert_eq!(glass.specular, Specular::dielectric(1.5, Vec3::ZERO));
    assert_eq!(glass.albedo, Vec3::ZERO);
    let green = material(&scene, "green_glass");
    assert_eq!(green.specular, Specular::dielectric(1.33, Vec3::new(0.5, 0.0, 0.5)));
    assert_eq!(green.roughness, 0.1);
}

#[test]
fn textures_and_phong_terms() {
    let scene = load(&format!(
        "{CAMERA}[materials.floor]\n\
         texture = {{ type = \"checker2d\", scale = 8.0, even = [0.9, 0.9, 0.9], odd = [0.1, 0.1, 0.1] }}\n\
         [materials.solid]\ntype = \"mirror\"\n\
         texture = {{ type = \"checker3d\", scale = 0.5, even = [1, 0, 0], odd = [0, 0, 1] }}\n\
         phong = {{ ambient = [0.1, 0.1, 0.1], specular = [1, 1, 1], exponent = 50 }}\n\
         [materials.course]\nphong = {{ specular = [0.5, 0.5, 0.5] }}\n"
    ));
    let floor = material(&scene, "floor").texture.clone().unwrap();
    assert_eq!(
        floor.pattern,
        Pattern::Checker2d { scale: 8.0, even: Vec3::splat(0.9), odd: Vec3::splat(0.1) }
    );
    assert_eq!(floor.texture_from_object, DAffine3::IDENTITY);
    let solid = material(&scene, "solid");
    assert_eq!(
        solid.texture.as_ref().unwrap().pattern,
        Pattern::Checker3d { scale: 0.5, even: Vec3::X, odd: Vec3::Z }
    );
    assert_eq!(
        solid.phong,
        Some(PhongDesc {
            ambient: Vec3::splat(0.1),
            specular: Vec3::ONE,
            exponent: 50.0,
            brdf: Default::default()
        })
    );
    assert_eq!(
        material(&scene, "course").phong,
        Some(PhongDesc {
            ambient: Vec3::ZERO,
            specular: Vec3::splat(0.5),
            exponent: 1.0,
            brdf: Default::default()
        })
    );
    assert_eq!(material(&scene, "floor").phong, None);
}

#[test]
fn with_texture_space_attaches_a_texture_to_an_instance() {
    let scene = load(&format!(
        "{CAMERA}[materials.solid]\n\
         texture = {{ type = \"checker3d\", scale = 1.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    let instance = DAffine3::from_scale(DVec3::splat(0.5));
    let attached = scene::with_texture_space(&scene.materials[0], instance);
    assert_eq!(attached.texture.as_ref().unwrap().texture_from_object, instance);
    assert_eq!(attached.name, "solid");
    // The original is unchanged.
    assert_eq!(
        scene.materials[0].texture.as_ref().unwrap().texture_from_object,
        DAffine3::IDENTITY
    );
}

/// hw6's BRDFs and the photographic tone mapping in TOML (what `embray convert` writes).
#[test]
fn course_brdfs_and_photographic_tonemap() {
    use embray::scene::CourseBrdf;
    let scene = load(&format!(
        "{CAMERA}[render]\ntonemap = {{ operator = \"photographic\", key = 0.3, burn_out = 0 }}\n\
         [materials.gold]\nalbedo = [0.5, 0.43, 0.285]\n\
         phong = {{ specular = [1, 0.86, 0.57], exponent = 10 }}\n\
         brdf = {{ model = \"torrance_sparrow\", exponent = 50, kd_fresnel = true, eta = 0.37, k = 2.82 }}\n\
         [materials.lobe]\nbrdf = {{ model = \"modified_phong\", normalized = true }}\n"
    ));
    let tonemap = scene.settings.tonemap.unwrap();
    assert_eq!((tonemap.key, tonemap.burn_out, tonemap.gamma), (0.3, 0.0, 2.2));
    let gold = material(&scene, "gold").phong.clone().unwrap();
    assert_eq!(gold.exponent, 50.0);
    assert_eq!(
        gold.brdf,
        CourseBrdf::TorranceSparrow {
            kd_fresnel: true,
            eta: Vec3::splat(0.37),
            k: Vec3::splat(2.82)
        }
    );
    let lobe = material(&scene, "lobe").phong.clone().unwrap();
    assert_eq!(
        (lobe.brdf, lobe.specular),
        (CourseBrdf::ModifiedPhong { normalized: true }, Vec3::ZERO)
    );
    for (text, needles) in [
        (
            "brdf = { model = \"torrance_sparrow\", normalized = true, eta = 1 }",
            &["brdf.normalized", "only for the modified"][..],
        ),
        ("brdf = { model = \"torrance_sparrow\" }", &["eta"][..]),
        ("brdf = { model = \"phong\" }", &["model"][..]),
        ("brdf = { model = \"modified_phong\", exponent = 0 }", &["brdf.exponent", "> 0"][..]),
    ] {
        let toml = format!("{CAMERA}[materials.m]\n{text}\n");
        let message = scene::load_str(&toml, &source()).unwrap_err().to_string();
        for needle in needles {
            assert!(message.contains(needle), "{text}: {message}");
        }
    }
    let toml =
        format!("{CAMERA}[render]\ntonemap = {{ operator = \"photographic\", gamma = 0 }}\n");
    let message = scene::load_str(&toml, &source()).unwrap_err().to_string();
    assert!(message.contains("render.tonemap") && message.contains("gamma"), "{message}");
}

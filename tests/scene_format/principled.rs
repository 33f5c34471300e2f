//! `type = "principled"` and `"principledthin"`: Mitsuba's parameters in a `principled`
//! table, each a number or a texture, with Mitsuba's defaults.

use super::*;
use embray::scene::{ParamDesc, eta_from_specular};

#[test]
fn principled_materials_read_with_mitsubas_defaults() {
    let scene = load(&scene_with(
        r#"
[materials.plain]
type = "principled"

[materials.paint]
type = "principled"
albedo = [0.2, 0.8, 0.1]
principled = { roughness = 0.15, specular = 0.7, metallic = { type = "checker2d", scale = 50, even = [0.1, 0.1, 0.1], odd = [0.7, 0.7, 0.7] }, clearcoat_sampling_rate = 0.5 }

[materials.sheet]
type = "principledthin"
texture = { type = "checker2d", scale = 4, even = [0.1, 0.2, 0.3], odd = [0.5, 0.5, 0.5] }

[materials.sheet.principled]
diff_trans = { type = "checker2d", scale = 25, even = [1.4, 1.4, 1.4], odd = [0.4, 0.4, 0.4] }
eta = 1.33
"#,
    ));
    let plain = material(&scene, "plain");
    let p = plain.principled.as_deref().unwrap();
    assert_eq!((plain.albedo, plain.specular), (Vec3::splat(0.5), Specular::None));
    assert_eq!(
        (p.thin, &p.roughness, &p.eta),
        (false, &ParamDesc::Constant(0.5), &ParamDesc::Constant(1.5))
    );

    let paint = material(&scene, "paint");
    let p = paint.principled.as_deref().unwrap();
    assert_eq!(paint.albedo, Vec3::new(0.2, 0.8, 0.1));
    assert_eq!(p.roughness, ParamDesc::Constant(0.15));
    assert_eq!(p.eta, ParamDesc::Constant(eta_from_specular(0.7)));
    assert!(
        matches!(&p.metallic, ParamDesc::Texture(t) if matches!(t.pattern, Pattern::Checker2d { .. }))
    );
    assert_eq!(p.sampling_rates.clearcoat, 0.5);

    let sheet = material(&scene, "sheet");
    let p = sheet.principled.as_deref().unwrap();
    assert!(p.thin && sheet.texture.is_some());
    assert_eq!(p.eta, ParamDesc::Constant(1.33));
    let ParamDesc::Texture(t) = &p.diff_trans else { panic!("{:?}", p.diff_trans) };
    assert!(matches!(t.pattern, Pattern::Checker2d { even, .. } if even == Vec3::splat(1.4)));
}

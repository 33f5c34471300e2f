//! Principled materials: each parameter's range, the fields each model takes, and the
//! table only where a principled material is.

use super::*;

#[test]
fn principled_parameters_out_of_range_or_misplaced_are_refused() {
    let cases = [
        (
            "type = \"principled\"\nprincipled = { roughness = 1.5 }",
            &["roughness", "1.5", "in [0, 1]"][..],
        ),
        ("type = \"principled\"\nprincipled = { eta = 1.4, specular = 0.5 }", &["eta", "specular"]),
        ("type = \"principled\"\nprincipled = { eta = 0 }", &["eta", "> 0"]),
        ("type = \"principled\"\nprincipled = { diff_trans = 1 }", &["diff_trans", "principled"]),
        (
            "type = \"principledthin\"\nprincipled = { metallic = 0.5 }",
            &["metallic", "principledthin"],
        ),
        (
            "type = \"principledthin\"\nprincipled = { diff_trans = 2.5 }",
            &["diff_trans", "in [0, 2]"],
        ),
        (
            "type = \"principled\"\nprincipled = { eta = { type = \"constant\", value = [1, 1, 1] } }",
            &["eta", "a number (a texture only in principledthin)"],
        ),
        ("type = \"principled\"\nprincipled = { sheen_tint = -0.1 }", &["sheen_tint", "-0.1"]),
        ("type = \"principled\"\nprincipled = { roughnes = 0.5 }", &["roughnes"]),
        ("type = \"principled\"\nphong = { specular = [1, 1, 1], exponent = 10 }", &["phong"]),
        ("type = \"diffuse\"\nprincipled = { roughness = 0.5 }", &["principled"]),
    ];
    for (material, expected) in cases {
        let text = scene_with(&format!("[materials.p]\n{material}\n"));
        let message = load_err(&text);
        assert_contains(&message, expected);
        assert_contains(&message, &["line"]);
    }
}

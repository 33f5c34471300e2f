//! The scene loader on bad (and good) input: every error names the file, the field or line,
//! and the offending value; nothing panics. CLI-level tests live elsewhere.

use embray::scene::{self, LightDesc, SceneDesc, ShapeDesc};
use glam::{DVec3, Vec3};
use std::path::{Path, PathBuf};

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scene")
}

/// The (virtual) file the test scenes come from; OBJ paths resolve against its directory.
fn source() -> PathBuf {
    data_dir().join("scene.toml")
}

const CAMERA: &str = "\
[camera]
lookfrom = [0.0, 0.0, -5.0]
lookat = [0.0, 0.0, 0.0]
vfov = 40.0
resolution = [32, 24]
";

const WHITE: &str = "\
[materials.white]
albedo = [0.73, 0.73, 0.73]
";

fn load(text: &str) -> SceneDesc {
    match scene::load_str(text, &source()) {
        Ok(scene) => scene,
        Err(e) => panic!("scene should load, got: {e}"),
    }
}

fn load_err(text: &str) -> String {
    match scene::load_str(text, &source()) {
        Ok(_) => panic!("scene should be rejected:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[track_caller]
fn assert_contains(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "expected {part:?} in the message:\n{message}");
    }
}

/// `CAMERA`, the white material and `rest`.
fn scene_with(rest: &str) -> String {
    format!("{CAMERA}{WHITE}{rest}")
}

fn mesh_of(scene: &SceneDesc, object: usize) -> &embray::scene::MeshData {
    match &scene.objects[object].shape {
        ShapeDesc::Mesh(mesh) => mesh,
        other => panic!("object {object} is not a mesh: {other:?}"),
    }
}

// ---------------------------------------------------------------------------------------
// Files and syntax
// ---------------------------------------------------------------------------------------

#[test]
fn missing_scene_file_names_the_file() {
    let err = scene::load(Path::new("no/such/dir/absent_scene.toml")).unwrap_err().to_string();
    assert_contains(
        &err,
        &["scene file 'no/such/dir/absent_scene.toml'", "No such file or directory"],
    );
}

#[test]
fn toml_syntax_error_names_the_line() {
    let err = load_err("# comment\n\n[camera\nlookfrom = [0, 0, 0]\n");
    assert_contains(&err, &["scene.toml", "line 3, column 8"]);
}

#[test]
fn unknown_key_names_the_key_and_line() {
    let err = load_err(&format!("{CAMERA}fov = 3.0\n"));
    assert_contains(&err, &["scene.toml", "unknown field `fov`", "line 6"]);
}

#[test]
fn unknown_key_in_an_object_names_its_line() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\ncolour = 3\n",
    ));
    assert_contains(&err, &["scene.toml", "unknown field `colour`", "line 13"]);
}

#[test]
fn unknown_key_in_a_transform_entry_is_named() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ rotate = { axis = [0, 1, 0], degrees = 10, turns = 2 } }]\n",
    ));
    assert_contains(&err, &["scene.toml", "unknown field `turns`", "line 13, column 59"]);
}

#[test]
fn unknown_object_type_is_named() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"cone\"\nmaterial = \"white\"\n"));
    assert_contains(&err, &["scene.toml", "unknown variant `cone`", "line 9"]);
}

#[test]
fn wrong_array_length_names_the_line() {
    let err = load_err("[camera]\nlookfrom = [1.0, 2.0]\n");
    assert_contains(&err, &["scene.toml", "line 2", "expected an array of length 3"]);
}

#[test]
fn missing_required_field_is_named() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [1, 0, 0]\n",
    ));
    assert_contains(&err, &["scene.toml: objects[0] (quad) is missing the field `v`", "(line 8)"]);
}

#[test]
fn field_of_another_type_is_rejected() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [1, 0, 0]\nv = [0, 1, 0]\nradius = 2.0\n",
    ));
    assert_contains(
        &err,
        &["scene.toml: objects[0] (quad) does not take the field `radius`", "(line 14)"],
    );
}

// ---------------------------------------------------------------------------------------
// NaN and infinity, everywhere
// ---------------------------------------------------------------------------------------

#[test]
fn nan_in_camera_names_the_field_and_line() {
    let err =
        load_err(&CAMERA.replace("lookfrom = [0.0, 0.0, -5.0]", "lookfrom = [0.0, nan, -5.0]"));
    assert_contains(&err, &["scene.toml: camera.lookfrom[1] is NaN", "(line 2)"]);
}

#[test]
fn inf_radius_names_the_object() {
    let sphere = "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\n";
    let err = load_err(&scene_with(&format!(
        "{sphere}radius = 1.0\n{sphere}radius = 1.0\n{sphere}radius = inf\n"
    )));
    assert_contains(&err, &["scene.toml: objects[2].radius is inf", "(line 22)"]);
}

#[test]
fn nan_in_material_is_named() {
    let err = load_err(&format!("{CAMERA}[materials.white]\nalbedo = [0.5, 0.5, -nan]\n"));
    assert_contains(&err, &["scene.toml: materials.white.albedo[2] is NaN", "(line 7)"]);
}

#[test]
fn infinite_transform_entry_is_named() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ scale = 2.0 }, { rotate = { axis = [0, 1, 0], degrees = -inf } }]\n",
    ));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[1].rotate.degrees is -inf", "(line 13)"],
    );
}

#[test]
fn nan_in_render_background_is_named() {
    let err = load_err(&format!("{CAMERA}[render]\nbackground = [nan, 0, 0]\n"));
    assert_contains(&err, &["scene.toml: render.background[0] is NaN"]);
}

#[test]
fn non_finite_obj_vertex_names_the_obj_and_vertex() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"nan_vertex.obj\"\n"));
    assert_contains(
        &err,
        &[
            "nan_vertex.obj: vertex 2 has a non-finite coordinate 'nan'",
            "(line 3)",
            "objects[0]",
            "scene.toml",
        ],
    );
}

// ---------------------------------------------------------------------------------------
// Ranges
// ---------------------------------------------------------------------------------------

#[test]
fn zero_resolution_is_rejected() {
    let err = load_err(&CAMERA.replace("[32, 24]", "[32, 0]"));
    assert_contains(
        &err,
        &["scene.toml: camera.resolution[1] is 0, but must be between 1 and 16384", "(line 5)"],
    );
}

#[test]
fn resolution_above_16384_is_rejected() {
    let err = load_err(&CAMERA.replace("[32, 24]", "[16385, 24]"));
    assert_contains(&err, &["camera.resolution[0] is 16385", "between 1 and 16384"]);
}

#[test]
fn negative_resolution_is_a_type_error_with_line() {
    let err = load_err(&CAMERA.replace("[32, 24]", "[-32, 24]"));
    assert_contains(&err, &["scene.toml", "line 5", "integer `-32`"]);
}

#[test]
fn zero_spp_is_rejected() {
    let err = load_err(&format!("{CAMERA}[render]\nspp = 0\n"));
    assert_contains(&err, &["scene.toml: render.spp is 0, but must be >= 1", "(line 7)"]);
}

#[test]
fn vfov_outside_0_180_is_rejected() {
    for vfov in ["0.0", "180.0", "-10", "200.0"] {
        let err = load_err(&CAMERA.replace("vfov = 40.0", &format!("vfov = {vfov}")));
        assert_contains(&err, &["scene.toml: camera.vfov is", "between 0 and 180", "(line 4)"]);
    }
}

#[test]
fn non_positive_radius_is_rejected() {
    for radius in ["0.0", "-1.5"] {
        let err = load_err(&scene_with(&format!(
            "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = {radius}\n"
        )));
        assert_contains(
            &err,
            &[
                &format!("scene.toml: objects[0].radius is {}", radius.trim_end_matches(".0")),
                "> 0",
            ],
        );
    }
}

#[test]
fn negative_albedo_is_rejected() {
    let err = load_err(&format!("{CAMERA}[materials.grey]\nalbedo = [0.5, -0.1, 0.5]\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.grey.albedo[1] is -0.1, but must be in [0, 1]", "(line 7)"],
    );
}

#[test]
fn albedo_above_one_is_rejected() {
    let err = load_err(&format!("{CAMERA}[materials.grey]\nalbedo = [1.5, 0.5, 0.5]\n"));
    assert_contains(&err, &["materials.grey.albedo[0] is 1.5, but must be in [0, 1]"]);
}

#[test]
fn negative_emission_is_rejected() {
    let err = load_err(&format!("{CAMERA}[materials.lamp]\nemission = [1, 1, -2]\n"));
    assert_contains(&err, &["scene.toml: materials.lamp.emission[2] is -2, but must be >= 0"]);
}

#[test]
fn negative_light_intensity_is_rejected() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = [-1, 1, 1]\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: lights[0].intensity[0] is -1, but must be >= 0", "(line 9)"],
    );
}

#[test]
fn negative_quad_light_emission_is_rejected() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"quad\"\ncorner = [0, 1, 0]\nu = [1, 0, 0]\nv = [0, 0, 1]\nemission = [1, -1, 1]\n"
    ));
    assert_contains(&err, &["lights[0].emission[1] is -1"]);
}

#[test]
fn negative_aperture_and_zero_focus_distance_are_rejected() {
    let err = load_err(&format!("{CAMERA}aperture = -0.5\n"));
    assert_contains(&err, &["camera.aperture is -0.5, but must be >= 0"]);
    let err = load_err(&format!("{CAMERA}focus_distance = 0.0\n"));
    assert_contains(&err, &["camera.focus_distance is 0, but must be > 0"]);
}

// ---------------------------------------------------------------------------------------
// Camera
// ---------------------------------------------------------------------------------------

#[test]
fn lookfrom_equal_to_lookat_is_a_degenerate_camera() {
    let err = load_err(&CAMERA.replace("lookat = [0.0, 0.0, 0.0]", "lookat = [0.0, 0.0, -5.0]"));
    assert_contains(
        &err,
        &[
            "scene.toml: degenerate camera",
            "camera.lookfrom and camera.lookat are the same point [0, 0, -5]",
        ],
    );
}

#[test]
fn zero_up_vector_is_a_degenerate_camera() {
    let err = load_err(&format!("{CAMERA}up = [0, 0, 0]\n"));
    assert_contains(
        &err,
        &["scene.toml: degenerate camera", "camera.up [0, 0, 0] is the zero vector", "(line 6)"],
    );
}

#[test]
fn up_parallel_to_view_direction_is_allowed() {
    let scene = load(&format!("{CAMERA}up = [0, 0, 1]\n"));
    assert_eq!(scene.camera.up, DVec3::Z);
}

// ---------------------------------------------------------------------------------------
// Materials
// ---------------------------------------------------------------------------------------

#[test]
fn unknown_material_lists_the_defined_ones() {
    let text = format!(
        "{CAMERA}{WHITE}[materials.light]\nemission = [4, 4, 4]\n\
         [[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\n\
         [[objects]]\ntype = \"sphere\"\nmaterial = \"red\"\ncenter = [0, 0, 0]\nradius = 1.0\n"
    );
    let err = load_err(&text);
    assert_contains(
        &err,
        &[
            "scene.toml: objects[1].material 'red' is not defined; defined: light, white",
            "(line 17)",
        ],
    );
}

#[test]
fn object_without_material_is_rejected() {
    let err =
        load_err(&scene_with("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1.0\n"));
    assert_contains(&err, &["objects[0] (sphere) is missing the field `material`"]);
}

// ---------------------------------------------------------------------------------------
// OBJ files
// ---------------------------------------------------------------------------------------

#[test]
fn missing_obj_file_names_the_obj_and_the_scene() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"models/absent.obj\"\n"));
    assert_contains(
        &err,
        &[
            "OBJ file '",
            "models/absent.obj'",
            "No such file or directory",
            "named by objects[0].file in '",
            "scene.toml' (line 10)",
        ],
    );
}

#[test]
fn obj_with_out_of_range_index_names_the_obj() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"bad_index.obj\"\n"));
    assert_contains(
        &err,
        &["bad_index.obj: a face refers to vertex 9, but the file has 3 vertices", "(line 5)"],
    );
}

#[test]
fn obj_without_triangles_is_rejected() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"no_triangles.obj\"\n"));
    assert_contains(&err, &["no_triangles.obj: the OBJ file has no triangles", "objects[0]"]);
}

#[test]
fn mtl_colour_with_two_numbers_is_an_error_not_a_panic() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"short_kd.obj\"\n"));
    assert_contains(&err, &["short_kd.mtl: Kd needs 3 numbers", "(line 2)"]);
}

// ---------------------------------------------------------------------------------------
// Transforms
// ---------------------------------------------------------------------------------------

const BOX: &str =
    "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n";

#[test]
fn zero_scale_is_a_singular_transform() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ translate = [1, 2, 3] }}, {{ scale = [1, 0, 1] }}]\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[1]: scale [1, 0, 1] is singular", "(line 13)"],
    );
}

#[test]
fn singular_matrix_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ matrix = [[1, 2, 3, 0], [2, 4, 6, 0], [0, 0, 1, 0], [0, 0, 0, 1]] }}]\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[0]: matrix is singular (determinant 0)"],
    );
}

#[test]
fn matrix_last_row_must_be_0001() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0.5, 1]] }}]\n"
    )));
    assert_contains(
        &err,
        &["objects[0].transform[0]: matrix last row is [0, 0, 0.5, 1], but must be [0, 0, 0, 1]"],
    );
}

#[test]
fn zero_rotation_axis_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ rotate = {{ axis = [0, 0, 0], degrees = 30 }} }}]\n"
    )));
    assert_contains(&err, &["objects[0].transform[0]: rotate axis [0, 0, 0] has zero length"]);
}

#[test]
fn transform_entry_with_two_keys_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}transform = [{{ scale = 2.0, translate = [1, 0, 0] }}]\n"
    )));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0].transform[0] must have exactly one of the keys scale, rotate, \
             translate, matrix; it has scale, translate",
            "(line 13)",
        ],
    );
}

#[test]
fn unknown_transform_kind_is_named() {
    let err = load_err(&scene_with(&format!("{BOX}transform = [{{ shear = 2.0 }}]\n")));
    assert_contains(&err, &["scene.toml", "unknown field `shear`", "line 13"]);
}

#[test]
fn singular_quad_light_transform_names_the_light() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"quad\"\ncorner = [0, 1, 0]\nu = [1, 0, 0]\nv = [0, 0, 1]\nemission = [1, 1, 1]\ntransform = [{{ scale = 0.0 }}]\n"
    ));
    assert_contains(&err, &["scene.toml: lights[0].transform[0]: scale [0, 0, 0] is singular"]);
}

#[test]
fn non_uniformly_scaled_sphere_is_an_ellipsoid_but_singular_is_rejected() {
    let sphere =
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\n";
    let scene = load(&scene_with(&format!("{sphere}transform = [{{ scale = [1, 2, 1] }}]\n")));
    let stretched = scene.objects[0].world_from_object.transform_vector3(DVec3::Y);
    assert_eq!(stretched, DVec3::new(0.0, 2.0, 0.0));
    let err = load_err(&scene_with(&format!(
        "{sphere}transform = [{{ matrix = [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]] }}]\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform[0]: matrix is singular (determinant 0)", "(line 13)"],
    );
}

// ---------------------------------------------------------------------------------------
// Degenerate shapes
// ---------------------------------------------------------------------------------------

#[test]
fn quad_with_parallel_edges_has_no_area() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [1, 1, 0]\nv = [2, 2, 0]\n",
    ));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0] (quad): u [1, 1, 0] and v [2, 2, 0] are zero or parallel",
            "(line 8)",
        ],
    );
}

#[test]
fn quad_light_with_zero_edge_has_no_area() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"quad\"\ncorner = [0, 1, 0]\nu = [0, 0, 0]\nv = [0, 0, 1]\nemission = [1, 1, 1]\n"
    ));
    assert_contains(
        &err,
        &["lights[0] (quad light): u [0, 0, 0] and v [0, 0, 1] are zero or parallel"],
    );
}

#[test]
fn box_with_min_not_below_max_is_rejected() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"box\"\nmaterial = \"white\"\nmin = [0, 2, 0]\nmax = [1, 1, 1]\n",
    ));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0] (box): min [0, 2, 0] must be less than max [1, 1, 1] on every axis, but not on y",
        ],
    );
}

// ---------------------------------------------------------------------------------------
// Camera lens and render settings
// ---------------------------------------------------------------------------------------

#[test]
fn aperture_and_f_number_together_are_rejected() {
    let err = load_err(&format!("{CAMERA}aperture = 0.1\nf_number = 2.0\nfocal_length = 0.05\n"));
    assert_contains(
        &err,
        &["scene.toml: camera takes `aperture` or `f_number`, not both (line 7)"],
    );
    let err = load_err(&format!("{CAMERA}aperture = 0.1\nfocal_length = 0.05\n"));
    assert_contains(&err, &["camera takes `aperture` or `focal_length`, not both (line 7)"]);
}

#[test]
fn f_number_and_focal_length_need_each_other() {
    let err = load_err(&format!("{CAMERA}f_number = 2.0\n"));
    assert_contains(
        &err,
        &["scene.toml: camera (with f_number) is missing the field `focal_length` (line 6)"],
    );
    let err = load_err(&format!("{CAMERA}focal_length = 0.05\n"));
    assert_contains(&err, &["camera (with focal_length) is missing the field `f_number` (line 6)"]);
}

#[test]
fn f_number_and_focal_length_must_be_positive() {
    let err = load_err(&format!("{CAMERA}f_number = 0.0\nfocal_length = 0.05\n"));
    assert_contains(&err, &["scene.toml: camera.f_number is 0, but must be > 0 (line 6)"]);
    let err = load_err(&format!("{CAMERA}f_number = 2.8\nfocal_length = -1\n"));
    assert_contains(&err, &["camera.focal_length is -1, but must be > 0 (line 7)"]);
}

#[test]
fn unknown_lens_shape_is_named() {
    let err = load_err(&format!("{CAMERA}lens = \"hexagon\"\n"));
    assert_contains(
        &err,
        &["scene.toml", "line 6", "unknown variant `hexagon`", "expected `disk` or `square`"],
    );
}

#[test]
fn zero_light_samples_and_unknown_integrator_are_rejected() {
    let err = load_err(&format!("{CAMERA}[render]\nlight_samples = 0\n"));
    assert_contains(&err, &["scene.toml: render.light_samples is 0, but must be >= 1 (line 7)"]);
    let err = load_err(&format!("{CAMERA}[render]\nintegrator = \"bdpt\"\n"));
    assert_contains(
        &err,
        &["scene.toml", "line 7", "unknown variant `bdpt`", "expected `path` or `whitted`"],
    );
}

// ---------------------------------------------------------------------------------------
// Material types
// ---------------------------------------------------------------------------------------

#[test]
fn unknown_material_type_is_named() {
    let err = load_err(&format!("{CAMERA}[materials.m]\ntype = \"plastic\"\n"));
    assert_contains(&err, &["scene.toml", "line 7", "unknown variant `plastic`"]);
}

#[test]
fn field_of_another_material_type_is_rejected() {
    let err = load_err(&format!("{CAMERA}{WHITE}roughness = 0.1\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.white (diffuse) does not take the field `roughness` \
             (it takes: type, albedo, emission, texture, phong) (line 8)"],
    );
    let err =
        load_err(&format!("{CAMERA}[materials.glass]\ntype = \"dielectric\"\neta = [1, 1, 1]\n"));
    assert_contains(
        &err,
        &[
            "materials.glass (dielectric) does not take the field `eta`",
            "ior, absorption",
            "(line 8)",
        ],
    );
    let err = load_err(&format!("{CAMERA}[materials.chrome]\ntype = \"mirror\"\nior = 1.5\n"));
    assert_contains(&err, &["materials.chrome (mirror) does not take the field `ior`"]);
    let err = load_err(&format!(
        "{CAMERA}[materials.gold]\ntype = \"conductor\"\npreset = \"gold\"\nabsorption = [1, 1, 1]\n"
    ));
    assert_contains(&err, &["materials.gold (conductor) does not take the field `absorption`"]);
}

#[test]
fn mirror_reflectance_and_roughness_are_checked() {
    let mirror = format!("{CAMERA}[materials.chrome]\ntype = \"mirror\"\n");
    let err = load_err(&format!("{mirror}reflectance = [1.0, 1.2, 1.0]\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.chrome.reflectance[1] is 1.2, but must be in [0, 1] (line 8)"],
    );
    let err = load_err(&format!("{mirror}roughness = -0.1\n"));
    assert_contains(&err, &["materials.chrome.roughness is -0.1, but must be >= 0 (line 8)"]);
}

#[test]
fn conductor_needs_eta_and_k_or_a_preset() {
    let metal = format!("{CAMERA}[materials.metal]\ntype = \"conductor\"\n");
    let err = load_err(&metal);
    assert_contains(
        &err,
        &["scene.toml: materials.metal (conductor) is missing the field `eta` (line 6)"],
    );
    let err = load_err(&format!("{metal}eta = [0.2, 0.9, 1.1]\n"));
    assert_contains(&err, &["materials.metal (conductor) is missing the field `k`"]);
    let err = load_err(&format!("{metal}preset = \"copper\"\neta = [0.2, 0.9, 1.1]\n"));
    assert_contains(
        &err,
        &["scene.toml: materials.metal (conductor) takes `preset` or `eta`, not both (line 9)"],
    );
    let err = load_err(&format!("{metal}preset = \"platinum\"\n"));
    assert_contains(&err, &["scene.toml", "line 8", "unknown variant `platinum`", "`gold`"]);
}

#[test]
fn conductor_eta_must_be_positive_and_k_non_negative() {
    let metal = format!("{CAMERA}[materials.metal]\ntype = \"conductor\"\n");
    let err = load_err(&format!("{metal}eta = [0.2, 0.0, 1.1]\nk = [3, 2, 2]\n"));
    assert_contains(&err, &["materials.metal.eta[1] is 0, but must be > 0 (line 8)"]);
    let err = load_err(&format!("{metal}eta = [0.2, 0.9, 1.1]\nk = [3, 2, -1]\n"));
    assert_contains(&err, &["materials.metal.k[2] is -1, but must be >= 0 (line 9)"]);
}

#[test]
fn dielectric_ior_and_absorption_are_checked() {
    let glass = format!("{CAMERA}[materials.glass]\ntype = \"dielectric\"\n");
    let err = load_err(&format!("{glass}ior = 0.0\n"));
    assert_contains(&err, &["scene.toml: materials.glass.ior is 0, but must be > 0 (line 8)"]);
    let err = load_err(&format!("{glass}absorption = [-1, 0, 0]\n"));
    assert_contains(&err, &["materials.glass.absorption[0] is -1, but must be >= 0 (line 8)"]);
}

#[test]
fn texture_fields_are_checked() {
    let floor = format!("{CAMERA}[materials.floor]\n");
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker2d\", scale = 0.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: materials.floor.texture.scale is 0, but must be > 0 (line 7)"],
    );
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker3d\", scale = 2.0, even = [1.5, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    assert_contains(&err, &["materials.floor.texture.even[0] is 1.5, but must be in [0, 1]"]);
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"marble\", scale = 2.0, even = [1, 1, 1], odd = [0, 0, 0] }}\n"
    ));
    assert_contains(&err, &["scene.toml", "line 7", "unknown variant `marble`"]);
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker2d\", scale = 2.0, even = [1, 1, 1] }}\n"
    ));
    assert_contains(&err, &["scene.toml", "line 7", "missing field `odd`"]);
    let err = load_err(&format!(
        "{floor}texture = {{ type = \"checker2d\", scale = 2.0, even = [1, 1, 1], odd = [0, 0, 0], rotation = 3 }}\n"
    ));
    assert_contains(&err, &["scene.toml", "line 7", "unknown field `rotation`"]);
}

#[test]
fn phong_exponent_must_be_positive() {
    let err = load_err(&format!(
        "{CAMERA}[materials.m]\nphong = {{ specular = [1, 1, 1], exponent = 0 }}\n"
    ));
    assert_contains(
        &err,
        &["scene.toml: materials.m.phong.exponent is 0, but must be > 0 (line 7)"],
    );
    let err = load_err(&format!("{CAMERA}[materials.m]\nphong = {{ ambient = [-0.1, 0, 0] }}\n"));
    assert_contains(&err, &["materials.m.phong.ambient[0] is -0.1, but must be >= 0"]);
}

// ---------------------------------------------------------------------------------------
// Motion, repeat, smooth
// ---------------------------------------------------------------------------------------

#[test]
fn singular_transform_end_is_named() {
    let err = load_err(&scene_with(&format!("{BOX}transform_end = [{{ scale = [1, 0, 1] }}]\n")));
    assert_contains(
        &err,
        &["scene.toml: objects[0].transform_end[0]: scale [1, 0, 1] is singular", "(line 13)"],
    );
    let err = load_err(&scene_with(&format!("{BOX}transform_end = [{{}}]\n")));
    assert_contains(
        &err,
        &[
            "objects[0].transform_end[0] must have exactly one of the keys",
            "it has none",
            "(line 13)",
        ],
    );
    let err = load_err(&scene_with(&format!(
        "{BOX}transform_end = [{{ scale = 1e-200 }}, {{ scale = 1e-200 }}]\n"
    )));
    assert_contains(&err, &["objects[0].transform_end: the composed transform is singular"]);
}

#[test]
fn repeat_counts_are_checked() {
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [2, 0, 2], spacing = [1, 1, 1] }}\n"
    )));
    assert_contains(
        &err,
        &["scene.toml: objects[0].repeat.count[1] is 0, but must be >= 1 (line 13)"],
    );
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [1000, 1000, 11], spacing = [1, 1, 1] }}\n"
    )));
    assert_contains(
        &err,
        &["objects[0].repeat.count is 1000 × 1000 × 11 = 11000000 copies, but must be at most \
             10000000 copies (line 13)"],
    );
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [-1, 1, 1], spacing = [1, 1, 1] }}\n"
    )));
    assert_contains(&err, &["scene.toml", "line 13", "integer `-1`"]);
    let err = load_err(&scene_with(&format!("{BOX}repeat = {{ count = [2, 1, 1] }}\n")));
    assert_contains(&err, &["scene.toml", "line 13", "missing field `spacing`"]);
}

#[test]
fn repeat_spacing_that_overflows_is_rejected() {
    let err = load_err(&scene_with(&format!(
        "{BOX}repeat = {{ count = [3, 1, 1], spacing = [1e308, 0, 0] }}\n"
    )));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0].repeat.spacing: the farthest copy's position overflows",
            "(line 13)",
        ],
    );
}

#[test]
fn smooth_is_for_meshes_only() {
    let err = load_err(&scene_with(
        "[[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1.0\nsmooth = true\n",
    ));
    assert_contains(
        &err,
        &["scene.toml: objects[0] (sphere) does not take the field `smooth`", "(line 13)"],
    );
}

#[test]
fn mesh_file_of_unknown_format_is_rejected() {
    let err = load_err(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"models/teapot.stl\"\n"));
    assert_contains(
        &err,
        &[
            "scene.toml: objects[0].file is '",
            "models/teapot.stl', but must be an OBJ (.obj) or PLY (.ply) file (line 10)",
        ],
    );
}

// ---------------------------------------------------------------------------------------
// New light types
// ---------------------------------------------------------------------------------------

#[test]
fn directional_light_needs_a_direction() {
    let light = format!("{CAMERA}[[lights]]\ntype = \"directional\"\n");
    let err = load_err(&format!("{light}direction = [0, 0, 0]\nirradiance = [1, 1, 1]\n"));
    assert_contains(
        &err,
        &["scene.toml: lights[0].direction is [0, 0, 0], but must be a non-zero vector (line 8)"],
    );
    let err = load_err(&format!("{light}direction = [0, -1, 0]\nirradiance = [1, 1, -1]\n"));
    assert_contains(&err, &["lights[0].irradiance[2] is -1, but must be >= 0 (line 9)"]);
    let err = load_err(&format!("{light}irradiance = [1, 1, 1]\n"));
    assert_contains(&err, &["lights[0] (directional light) is missing the field `direction`"]);
}

#[test]
fn light_fields_of_another_type_are_rejected() {
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"ambient\"\nradiance = [0.1, 0.1, 0.1]\nemission = [1, 1, 1]\n"
    ));
    assert_contains(
        &err,
        &[
            "scene.toml: lights[0] (ambient light) does not take the field `emission` (it takes: type, radiance) (line 9)",
        ],
    );
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\ntransform = []\n"
    ));
    assert_contains(&err, &["lights[0] (point light) does not take the field `transform`"]);
}

#[test]
fn sphere_light_needs_a_positive_radius() {
    let light = format!(
        "{CAMERA}[[lights]]\ntype = \"sphere\"\ncenter = [0, 3, 0]\nemission = [5, 5, 5]\n"
    );
    let err = load_err(&light);
    assert_contains(
        &err,
        &["scene.toml: lights[0] (sphere light) is missing the field `radius` (line 6)"],
    );
    let err = load_err(&format!("{light}radius = 0\n"));
    assert_contains(&err, &["lights[0].radius is 0, but must be > 0 (line 10)"]);
    let err = load_err(&format!("{light}radius = 0.5\ntransform = [{{ scale = 0 }}]\n"));
    assert_contains(&err, &["lights[0].transform[0]: scale [0, 0, 0] is singular"]);
}

#[test]
fn mesh_light_needs_a_file_and_emission() {
    let err = load_err(&format!("{CAMERA}[[lights]]\ntype = \"mesh\"\nemission = [1, 1, 1]\n"));
    assert_contains(&err, &["lights[0] (mesh light) is missing the field `file`"]);
    let err = load_err(&format!("{CAMERA}[[lights]]\ntype = \"mesh\"\nfile = \"cube.ply\"\n"));
    assert_contains(&err, &["lights[0] (mesh light) is missing the field `emission`"]);
    let err = load_err(&format!(
        "{CAMERA}[[lights]]\ntype = \"mesh\"\nfile = \"absent.ply\"\nemission = [1, 1, 1]\n"
    ));
    assert_contains(&err, &["PLY file '", "absent.ply'", "named by lights[0].file", "(line 8)"]);
}

// ---------------------------------------------------------------------------------------
// PLY files
// ---------------------------------------------------------------------------------------

fn ply_object(file: &str) -> String {
    scene_with(&format!("[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"{file}\"\n"))
}

#[test]
fn missing_ply_file_names_the_ply_and_the_scene() {
    let err = load_err(&ply_object("models/absent.ply"));
    assert_contains(
        &err,
        &[
            "PLY file '",
            "models/absent.ply': No such file or directory",
            "named by objects[0].file in '",
            "scene.toml' (line 11)",
        ],
    );
}

#[test]
fn ply_with_out_of_range_index_names_the_face_and_line() {
    let err = load_err(&ply_object("bad_index.ply"));
    assert_contains(
        &err,
        &[
            "bad_index.ply' (line 14): face 1 refers to vertex 3, but the file has 3 vertices",
            "named by objects[0].file",
        ],
    );
}

#[test]
fn ply_with_non_finite_vertex_names_the_vertex() {
    let err = load_err(&ply_object("nan_vertex.ply"));
    assert_contains(&err, &["nan_vertex.ply' (line 11): vertex 1 has a non-finite coordinate"]);
}

#[test]
fn ply_with_unsupported_property_type_names_it() {
    let err = load_err(&ply_object("bad_type.ply"));
    assert_contains(&err, &["bad_type.ply' (line 6): unsupported property type 'float16'"]);
}

#[test]
fn ply_without_faces_is_rejected() {
    let err = load_err(&ply_object("no_faces.ply"));
    assert_contains(&err, &["no_faces.ply': the PLY file has no faces (no face element)"]);
}

#[test]
fn truncated_binary_ply_is_reported() {
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
        property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
        end_header\n"
        .to_vec();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bytes.extend(c.to_le_bytes());
        }
    }
    bytes.push(3);
    bytes.extend(0i32.to_le_bytes());
    bytes.extend(1i32.to_le_bytes()); // the third index is missing
    let dir = std::env::temp_dir().join(format!("embray-truncated-ply-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("cut.ply"), &bytes).unwrap();
    let result = scene::load_str(
        &scene_with("[[objects]]\ntype = \"mesh\"\nmaterial = \"white\"\nfile = \"cut.ply\"\n"),
        &dir.join("scene.toml"),
    );
    std::fs::remove_dir_all(&dir).unwrap();
    let err = result.unwrap_err().to_string();
    assert_contains(
        &err,
        &["cut.ply': the data ends in face 0 of 1 (truncated file?)", "objects[0].file"],
    );
}

// ---------------------------------------------------------------------------------------
// Scenes that load
// ---------------------------------------------------------------------------------------

/// The example of the format documentation, with every object type, light type and
/// transform kind.
const EXAMPLE: &str = r#"
[camera]
lookfrom = [278.0, 273.0, -800.0]
lookat = [278.0, 273.0, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 39.3
resolution = [256, 256]
aperture = 0.0
focus_distance = 800.0

[render]
spp = 16
max_depth = 5
background = [0.0, 0.0, 0.0]

[materials.white]
albedo = [0.73, 0.73, 0.73]
emission = [0.0, 0.0, 0.0]

[materials.light]
emission = [4.0, 4.0, 4.0]

[[objects]]
type = "quad"
material = "white"
corner = [0.0, 0.0, 0.0]
u = [555.0, 0.0, 0.0]
v = [0.0, 0.0, 555.0]
transform = [
  { scale = [1.0, 2.0, 1.0] },
  { scale = 2.0 },
  { rotate = { axis = [0.0, 1.0, 0.0], degrees = 15.0 } },
  { translate = [265.0, 0.0, 295.0] },
  { matrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]] },
]

[[objects]]
type = "sphere"
material = "light"
center = [0.0, 0.0, 0.0]
radius = 1.0

[[objects]]
type = "box"
material = "white"
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]

[[objects]]
type = "mesh"
file = "two_materials.obj"

[[lights]]
type = "point"
position = [278.0, 500.0, 278.0]
intensity = [1000.0, 1000.0, 1000.0]

[[lights]]
type = "quad"
corner = [213.0, 548.7, 227.0]
u = [130.0, 0.0, 0.0]
v = [0.0, 0.0, 105.0]
emission = [17.0, 12.0, 4.0]
transform = [{ translate = [0.0, -0.1, 0.0] }]
"#;

#[test]
fn example_scene_with_every_feature_loads() {
    let scene = load(EXAMPLE);
    assert_eq!(scene.source, source());
    assert_eq!((scene.camera.width, scene.camera.height), (256, 256));
    assert_eq!(scene.camera.focus_distance, Some(800.0));
    assert_eq!((scene.settings.spp, scene.settings.max_depth), (16, 5));
    // quad, sphere, box, 2 OBJ models (one per MTL material), quad light.
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "objects[0] (quad)",
            "objects[1] (sphere)",
            "objects[2] (box)",
            "objects[3] (two_materials.obj: Panel)",
            "objects[3] (two_materials.obj: Panel)",
            "lights[1] (quad light)",
        ]
    );
    assert_eq!(
        scene.lights,
        [LightDesc::Point {
            position: DVec3::new(278.0, 500.0, 278.0),
            intensity: Vec3::splat(1000.0)
        }]
    );
    // light, white (the table, sorted by name), the two MTL materials, the quad light's.
    let materials: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        materials,
        [
            "light",
            "white",
            "two_materials.obj: Red",
            "two_materials.obj: Glow",
            "lights[1] (quad light)"
        ]
    );
    let quad_light = &scene.objects[5];
    let light_material = &scene.materials[quad_light.material as usize];
    assert_eq!(
        (light_material.albedo, light_material.emission),
        (Vec3::ZERO, Vec3::new(17.0, 12.0, 4.0))
    );
    assert_eq!(mesh_of(&scene, 2).indices.len(), 12);
    assert_eq!(mesh_of(&scene, 0).indices.len(), 2);
    assert_eq!(scene.objects[1].shape, ShapeDesc::Sphere { center: DVec3::ZERO, radius: 1.0 });
}

#[test]
fn transform_list_applies_in_listed_order() {
    // Scale y by 2, rotate 90° about +y, translate: the quad's corner+v = (0, 0, 1)
    // → scale (0, 0, 1) → rotate (1, 0, 0) → translate (11, 20, 30).
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0, 0, 0]\nu = [0, 1, 0]\nv = [0, 0, 1]\n\
         transform = [{ scale = [1, 2, 1] }, { rotate = { axis = [0, 1, 0], degrees = 90 } }, { translate = [10, 20, 30] }]\n",
    ));
    let object = &scene.objects[0];
    let mesh = mesh_of(&scene, 0);
    let world = |i: usize| object.world_from_object.transform_point3(mesh.positions[i]);
    assert!((world(3) - DVec3::new(11.0, 20.0, 30.0)).length() < 1e-12, "{}", world(3));
    // corner+u = (0, 1, 0) → (0, 2, 0) → (0, 2, 0) → (10, 22, 30).
    assert!((world(1) - DVec3::new(10.0, 22.0, 30.0)).length() < 1e-12, "{}", world(1));
}

#[test]
fn matrix_transform_is_row_major() {
    let scene = load(&scene_with(&format!(
        "{BOX}transform = [{{ matrix = [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]] }}]\n"
    )));
    let p = scene.objects[0].world_from_object.transform_point3(DVec3::X);
    assert_eq!(p, DVec3::new(5.0, 7.0, 7.0));
}

#[test]
fn defaults_apply_when_fields_are_absent() {
    let scene = load(&scene_with(BOX));
    assert_eq!(scene.camera.up, DVec3::Y);
    assert_eq!((scene.camera.aperture, scene.camera.focus_distance), (0.0, None));
    assert_eq!(scene.settings, embray::scene::RenderSettings::default());
    assert_eq!(scene.objects[0].world_from_object, glam::DAffine3::IDENTITY);
    let scene = load(&format!("{CAMERA}[materials.plain]\n"));
    assert_eq!(scene.materials[0].albedo, Vec3::splat(0.8));
    assert_eq!(scene.materials[0].emission, Vec3::ZERO);
}

#[test]
fn obj_with_mtl_colours_loads_one_object_per_material() {
    let scene = load(&scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\n"));
    assert_eq!(scene.objects.len(), 2);
    let material = |i: usize| &scene.materials[scene.objects[i].material as usize];
    assert_eq!(material(0).name, "two_materials.obj: Red");
    assert_eq!((material(0).albedo, material(0).emission), (Vec3::new(0.7, 0.1, 0.1), Vec3::ZERO));
    assert_eq!(material(1).name, "two_materials.obj: Glow");
    assert_eq!((material(1).albedo, material(1).emission), (Vec3::ZERO, Vec3::new(4.0, 3.0, 2.0)));
    for i in 0..2 {
        let mesh = mesh_of(&scene, i);
        assert_eq!(mesh.indices.len(), 1);
        assert_eq!(mesh.normals.as_ref().unwrap()[0], DVec3::Z);
        assert_eq!(mesh.uvs.as_ref().unwrap().len(), mesh.positions.len());
    }
}

#[test]
fn material_in_scene_overrides_the_obj_materials() {
    let scene = load(&scene_with(
        "[[objects]]\ntype = \"mesh\"\nfile = \"two_materials.obj\"\nmaterial = \"white\"\n",
    ));
    assert!(scene.objects.iter().all(|o| scene.materials[o.material as usize].name == "white"));
    assert_eq!(scene.materials.len(), 1);
}

#[test]
fn obj_naming_a_missing_mtl_loads_with_a_warning() {
    let (scene, warnings) = scene::load_str_with_warnings(
        &scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"missing_mtl.obj\"\n"),
        &source(),
    )
    .unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_contains(&warnings[0], &["missing_mtl.obj", "does_not_exist.mtl"]);
    assert_eq!(scene.objects.len(), 1);
    let material = &scene.materials[scene.objects[0].material as usize];
    assert_eq!((material.albedo, material.emission), (Vec3::splat(0.8), Vec3::ZERO));
}

#[test]
fn scene_file_on_disk_loads_and_resolves_obj_paths() {
    let dir = std::env::temp_dir().join(format!("embray-scene-test-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("models")).unwrap();
    std::fs::copy(data_dir().join("two_materials.obj"), dir.join("models/two_materials.obj"))
        .unwrap();
    std::fs::copy(data_dir().join("two_materials.mtl"), dir.join("models/two_materials.mtl"))
        .unwrap();
    let path = dir.join("on_disk.toml");
    std::fs::write(
        &path,
        scene_with("[[objects]]\ntype = \"mesh\"\nfile = \"models/two_materials.obj\"\n"),
    )
    .unwrap();
    let result = scene::load(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(result.unwrap().objects.len(), 2);
}

#[test]
fn bundled_scenes_load() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(!scene.objects.is_empty(), "{}", path.display());
            count += 1;
        }
    }
    assert!(count > 0, "no scenes in {}", dir.display());
}

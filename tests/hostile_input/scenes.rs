//! Scene files that are malformed, huge or deep: clear messages with the file and line,
//! short excerpts of huge values, and no stack depth that comes from the input.

use crate::harness::{Scratch, accepted_in, refused_cases, refused_in, scene};

/// Two mirrors 2 apart facing each other, the camera between them looking at one: every
/// camera ray bounces between them until `depth` runs out (Whitted, TOML).
pub fn mirror_box_toml(depth: u32, size: u32) -> String {
    format!(
        r#"[camera]
lookfrom = [0.0, 0.0, 0.0]
lookat = [0.0, 0.0, 1.0]
vfov = 10.0
resolution = [{size}, {size}]

[render]
spp = 1
max_depth = {depth}
integrator = "whitted"

[materials.mirror]
type = "mirror"
reflectance = [0.9, 0.9, 0.9]

[[objects]]
type = "quad"
material = "mirror"
corner = [-1000.0, -1000.0, 1.0]
u = [0.0, 2000.0, 0.0]
v = [2000.0, 0.0, 0.0]

[[objects]]
type = "quad"
material = "mirror"
corner = [-1000.0, -1000.0, -1.0]
u = [2000.0, 0.0, 0.0]
v = [0.0, 2000.0, 0.0]

[[lights]]
type = "point"
position = [0.0, 0.5, 0.0]
intensity = [100.0, 100.0, 100.0]
"#
    )
}

/// The same mirrors as a CENG795 scene (image `mirrors.png`, 8×8).
pub fn mirror_box_xml(depth: u32) -> String {
    format!(
        r#"<Scene>
  <MaxRecursionDepth>{depth}</MaxRecursionDepth>
  <Cameras>
    <Camera id="1">
      <Position>0 0 0</Position><Gaze>0 0 1</Gaze><Up>0 1 0</Up>
      <NearPlane>-0.05 0.05 -0.05 0.05</NearPlane><NearDistance>1</NearDistance>
      <ImageResolution>8 8</ImageResolution><ImageName>mirrors.png</ImageName>
    </Camera>
  </Cameras>
  <Lights><PointLight id="1"><Position>0 0.5 0</Position><Intensity>1000 1000 1000</Intensity></PointLight></Lights>
  <Materials>
    <Material id="1" type="mirror">
      <AmbientReflectance>0 0 0</AmbientReflectance><DiffuseReflectance>0.1 0.1 0.1</DiffuseReflectance>
      <SpecularReflectance>0 0 0</SpecularReflectance><MirrorReflectance>0.9 0.9 0.9</MirrorReflectance>
    </Material>
  </Materials>
  <VertexData>-1000 -1000 1  1000 -1000 1  1000 1000 1  -1000 1000 1
              -1000 -1000 -1  1000 -1000 -1  1000 1000 -1  -1000 1000 -1</VertexData>
  <Objects>
    <Mesh id="1"><Material>1</Material><Faces>1 3 2  1 4 3  5 6 7  5 7 8</Faces></Mesh>
  </Objects>
</Scene>
"#
    )
}

#[test]
fn whitted_depth_2000_between_mirrors_renders_64x64() {
    let scratch = Scratch::new();
    scratch.write("mirrors.toml", mirror_box_toml(2000, 64));
    let run = accepted_in(&scratch, &["render", "mirrors.toml", "-o", "m.exr", "--stats"]);
    // The rays really bounce: far more indirect rays than camera rays.
    let indirect: u64 = run
        .stdout
        .lines()
        .find(|l| l.starts_with("indirect"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(indirect > 64 * 64 * 1000, "{indirect} indirect rays");
}

refused_cases! {
    define_with_a_toml_scene: ["s.toml" => scene("")], ["render", "s.toml", "-D", "spp=64"]
        => ["s.toml", "-D spp=64", "parameters are for Mitsuba 3 scenes", "a TOML scene"];
    define_with_a_ceng795_scene: ["s.xml" => crate::harness::xml_scene(&["s.png"], "")], ["render", "s.xml", "-D", "spp=64"]
        => ["s.xml", "-D spp=64", "a CENG795 scene"];
    define_with_the_built_in_scene: [], ["info", "-D", "spp=64"]
        => ["-D spp=64", "the built-in Cornell box"];
    define_the_mitsuba_scene_does_not_name: ["s.xml" => MITSUBA_WITH_SPP.to_owned()], ["render", "s.xml", "-D", "sp=64"]
        => ["s.xml", "-D sp=64", "the scene has no parameter `sp`", "its parameters: spp"];
    fifty_megabyte_string_under_an_unknown_key: ["s.toml" => scene(&format!("junk = \"{}\"\n", "x".repeat(5_000_000)))], ["render", "s.toml"]
        => ["s.toml", "does not take the field `junk`", "line 24"];
    huge_material_name: ["s.toml" => scene("").replace("material = \"grey\"", &format!("material = \"{}\"", "m".repeat(1_000_000)))], ["render", "s.toml"]
        => ["s.toml", "objects[0].material", "characters)"];
    unterminated_string: ["s.toml" => scene("[extra]\nx = \"open\n")], ["render", "s.toml"]
        => ["s.toml", "line 25"];
    nan_in_the_camera: ["s.toml" => scene("").replace("vfov = 60.0", "vfov = nan")], ["render", "s.toml"]
        => ["s.toml", "camera.vfov", "(line 4)"];
    resolution_zero: ["s.toml" => scene("").replace("[8, 8]", "[0, 8]")], ["render", "s.toml"]
        => ["s.toml", "camera.resolution", "(line 5)"];
    spp_absurd_in_the_scene: ["s.toml" => scene("").replace("spp = 1", "spp = 2000000")], ["render", "s.toml"]
        => ["s.toml", "render.spp", "between 1 and 1048576", "(line 8)"];
    light_samples_four_billion: ["s.toml" => scene("").replace("spp = 1", "spp = 1\nlight_samples = 4000000000")], ["render", "s.toml"]
        => ["s.toml", "render.light_samples", "between 1 and 65536", "(line 9)"];
    max_depth_absurd_in_the_scene: ["s.toml" => scene("").replace("spp = 1", "spp = 1\nmax_depth = 4000000000")], ["render", "s.toml"]
        => ["s.toml", "render.max_depth", "at most 100000", "(line 9)"];
    f_number_infinitely_fast: ["s.toml" => scene("").replace("resolution = [8, 8]", "resolution = [8, 8]\nf_number = 1e-300\nfocal_length = 50.0")], ["render", "s.toml"]
        => ["s.toml", "camera.f_number", "at least 0.01", "(line 6)"];
    repeat_ten_million_copies: ["s.toml" => scene("").replace("v = [2.0, 0.0, 0.0]", "v = [2.0, 0.0, 0.0]\nrepeat = { count = [1000, 1000, 10], spacing = [3.0, 3.0, 3.0] }")], ["render", "s.toml"]
        => ["s.toml", "objects[0].repeat.count", "at most 1000000 copies"];
    repeat_copies_beyond_the_coordinate_range: ["s.toml" => scene("").replace("v = [2.0, 0.0, 0.0]", "v = [2.0, 0.0, 0.0]\nrepeat = { count = [20, 1, 1], spacing = [1e7, 0.0, 0.0] }")], ["render", "s.toml"]
        => ["s.toml", "objects[0] is 1.", "copy", "coordinate range ±1e8", "(line 13)"];
    unknown_material_named: ["s.toml" => scene("").replace("material = \"grey\"", "material = \"gold\"")], ["render", "s.toml"]
        => ["s.toml", "gold", "not defined"];
    scene_missing: [], ["render", "nothing.toml"]
        => ["nothing.toml", "No such file"];
    xml_malformed: ["s.xml" => "<Scene>\n<Cameras>\n</Scene>\n"], ["render", "s.xml"]
        => ["s.xml", "malformed XML", "line 3"];
    info_on_a_bad_scene: ["s.toml" => scene("").replace("albedo = [0.5, 0.5, 0.5]", "albedo = [2.0, 0.5, 0.5]")], ["info", "s.toml"]
        => ["s.toml", "materials.grey.albedo", "line 11"];
}

/// `scene` rendered by the Whitted integrator, its grey material given `fields` too.
fn whitted_with(fields: &str) -> String {
    scene("")
        .replace("spp = 1", "spp = 1\nintegrator = \"whitted\"")
        .replace("albedo = [0.5, 0.5, 0.5]", &format!("albedo = [0.5, 0.5, 0.5]\n{fields}"))
}

// Whitted shades the course's model only: these rendered as plain diffuse without a word.
refused_cases! {
    whitted_with_a_principled_material: ["s.toml" => whitted_with("type = \"principled\"")], ["render", "s.toml"]
        => ["s.toml", "materials.grey.type is principled", "whitted integrator cannot shade a principled BSDF", "(line 13)"];
    whitted_with_opacity: ["s.toml" => whitted_with("opacity = 0.2")], ["render", "s.toml"]
        => ["s.toml", "materials.grey.opacity is 0.2", "cannot shade partial opacity", "(line 13)"];
    whitted_with_a_blend: ["s.toml" => whitted_with("").replace("[materials.grey]", "[materials.m]\ntype = \"mirror\"\n[materials.grey]\ntype = \"blend\"\nweight = 0.5\nmaterials = [\"m\", \"m\"]").replace("albedo = [0.5, 0.5, 0.5]\n", "")], ["render", "s.toml"]
        => ["s.toml", "materials.grey.type is blend", "cannot shade a blend", "(line 14)"];
    principled_sampling_rates_all_zero: ["s.toml" => scene("").replace("albedo = [0.5, 0.5, 0.5]", "type = \"principled\"\nprincipled = { main_specular_sampling_rate = 0.0, clearcoat_sampling_rate = 0.0, diffuse_reflectance_sampling_rate = 0.0 }")], ["render", "s.toml"]
        => ["s.toml", "materials.grey.principled.diffuse_reflectance_sampling_rate is 0", "at least one lobe must be sampled", "(line 12)"];
}

#[test]
fn out_dir_with_a_toml_scene_is_warned_about() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let run = accepted_in(&scratch, &["render", "s.toml", "--out-dir", "elsewhere", "-q"]);
    run.assert_says(&["--out-dir is used for CENG795 .xml scenes only"]);
    assert!(scratch.path("s.exr").is_file() && !scratch.path("elsewhere").exists());
}

#[test]
fn aovs_without_an_exr_are_warned_about() {
    let scratch = Scratch::new();
    scratch.write("s.toml", scene(""));
    let run = accepted_in(&scratch, &["render", "s.toml", "-o", "s.png", "--aovs", "albedo", "-q"]);
    run.assert_says(&["--aovs chooses the EXR's channels, and no EXR is written"]);
    assert!(scratch.path("s.png").is_file() && !scratch.path("s.exr").exists());
    let run = accepted_in(&scratch, &["render", "s.toml", "-o", "s.exr", "--aovs", "albedo", "-q"]);
    assert!(!run.stderr.contains("--aovs"), "{}", run.stderr);
}

#[test]
fn a_scene_that_is_a_folder_is_refused() {
    let scratch = Scratch::new();
    std::fs::create_dir(scratch.path("d.toml")).unwrap();
    refused_in(&scratch, &["render", "d.toml"], &["d.toml", "a directory, not a regular file"]);
}

/// A Mitsuba scene whose one parameter is `spp`.
pub(crate) const MITSUBA_WITH_SPP: &str = r#"<scene version="3.0.0">
    <default name="spp" value="1"/>
    <sensor type="perspective">
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <shape type="sphere"/>
    <emitter type="constant"/>
</scene>
"#;

/// A parameter the scene names renders.
#[test]
fn a_define_the_mitsuba_scene_names_is_used() {
    let scratch = Scratch::new();
    scratch.write("s.xml", MITSUBA_WITH_SPP);
    let run = accepted_in(&scratch, &["info", "s.xml", "-D", "spp=3"]);
    assert!(run.stdout.contains("render: 3 spp"), "{}", run.stdout);
}

/// A parameter defaulted twice keeps its first value, as Mitsuba 3 keeps it; `-D` is
/// above both.
#[test]
fn a_parameter_defaulted_twice_keeps_its_first_value() {
    let scratch = Scratch::new();
    let twice = r#"<default name="spp" value="1"/>
    <default name="spp" value="5"/>"#;
    scratch.write("s.xml", MITSUBA_WITH_SPP.replace(r#"<default name="spp" value="1"/>"#, twice));
    let run = accepted_in(&scratch, &["info", "s.xml"]);
    assert!(run.stdout.contains("render: 1 spp"), "{}", run.stdout);
    let run = accepted_in(&scratch, &["info", "s.xml", "-D", "spp=3"]);
    assert!(run.stdout.contains("render: 3 spp"), "{}", run.stdout);
}

//! CENG795 scenes name their own output files: an ImageName may not leave --out-dir, and two
//! cameras may not write the same file.

use crate::harness::{Scratch, accepted_in, refused_cases, xml_scene};

/// Glass spheres inside a mirror sphere at MaxRecursionDepth 40: every hit branches in two
/// and no ray escapes, so a sample's tree would take days. It ends at its ray limit, and a
/// warning says how many samples were cut.
#[test]
fn a_ray_tree_that_branches_at_every_hit_ends_at_its_limit() {
    let scratch = Scratch::new();
    scratch.write("glass.xml", GLASS_IN_A_MIRROR);
    let run = accepted_in(&scratch, &["render", "glass.xml", "--threads", "2", "--stats"]);
    run.assert_says(&["4 samples' reflection and refraction trees reached 65536 rays"]);
    assert!(run.stdout.contains("cut trees        4"), "{}", run.stdout);
    assert!(scratch.path("img.png").is_file());
}

const GLASS_IN_A_MIRROR: &str = r#"<Scene><MaxRecursionDepth>40</MaxRecursionDepth><Cameras><Camera id="1"><Position>0 0 15</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>2 2</ImageResolution><ImageName>img.png</ImageName></Camera></Cameras><Lights><AmbientLight>25 25 25</AmbientLight><PointLight id="1"><Position>0 0 0</Position><Intensity>1000 1000 1000</Intensity></PointLight></Lights><Materials><Material id="1" type="dielectric"><AmbientReflectance>0.1 0.1 0.1</AmbientReflectance><DiffuseReflectance>0 0 0</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance><MirrorReflectance>1 1 1</MirrorReflectance><RefractionIndex>1.5</RefractionIndex><AbsorptionCoefficient>0 0 0</AbsorptionCoefficient></Material><Material id="2" type="mirror"><AmbientReflectance>0.1 0.1 0.1</AmbientReflectance><DiffuseReflectance>0.1 0.1 0.1</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance><MirrorReflectance>0.9 0.9 0.9</MirrorReflectance></Material></Materials><Transformations></Transformations><VertexData>0 0 0</VertexData><Objects><Sphere id="1"><Material>2</Material><Center>1</Center><Radius>20</Radius></Sphere><Sphere id="2"><Material>1</Material><Center>1</Center><Radius>10</Radius></Sphere><Sphere id="3"><Material>1</Material><Center>1</Center><Radius>5</Radius></Sphere></Objects></Scene>"#;

refused_cases! {
    image_name_climbing_out: ["s.xml" => xml_scene(&["../../x.png"], "")], ["render", "s.xml", "--out-dir", "out"]
        => ["s.xml", "ImageName", "'..'", "(line 12)"];
    image_name_absolute: ["s.xml" => xml_scene(&["/tmp/embray-hostile-abs.png"], "")], ["render", "s.xml"]
        => ["s.xml", "absolute path", "(line 12)"];
    two_cameras_one_image_name: ["s.xml" => xml_scene(&["a.png", "a.png"], "")], ["render", "s.xml"]
        => ["s.xml", "Camera id=\"2\"", "same output files", "line 5"];
    two_cameras_one_stem: ["s.xml" => xml_scene(&["a.png", "./a.jpg"], "")], ["render", "s.xml"]
        => ["same output files"];
    num_samples_absurd: ["s.xml" => xml_scene(&["a.png"], "").replace("<ImageName>", "<NumSamples>1000000000</NumSamples><ImageName>")], ["render", "s.xml"]
        => ["s.xml", "NumSamples", "1000000000", "between 1 and 1048576"];
    recursion_depth_absurd: ["s.xml" => xml_scene(&["a.png"], "<MaxRecursionDepth>1000000</MaxRecursionDepth>")], ["render", "s.xml"]
        => ["s.xml", "MaxRecursionDepth", "at most 100000", "(line 3)"];
    image_name_huge: ["s.xml" => xml_scene(&[&format!("{}.png", "n".repeat(100_000))], "")], ["render", "s.xml"]
        => ["s.xml", "characters)"];
    several_cameras_with_one_output_name: ["s.xml" => xml_scene(&["a.png", "b.png"], "")], ["render", "s.xml", "-o", "x.exr"]
        => ["-o names one file", "2 cameras"];
}

#[test]
fn image_names_in_subfolders_stay_inside_out_dir() {
    let scratch = Scratch::new();
    scratch.write("s.xml", xml_scene(&["sub/a.png", "b.png"], ""));
    accepted_in(&scratch, &["render", "s.xml", "--out-dir", "out", "-q"]);
    for file in ["out/sub/a.png", "out/sub/a.exr", "out/b.png", "out/b.exr"] {
        assert!(scratch.path(file).is_file(), "{file} missing");
    }
}

/// An ImageName's extension decides the display image (a JPEG for .jpg: it was a PNG under
/// the JPEG's name) where it names one embray writes; any other name is kept whole, not cut
/// at its last dot (`img_1.5` gave img_1.png).
#[test]
fn image_names_keep_their_format_and_their_dots() {
    let scratch = Scratch::new();
    scratch.write("s.xml", xml_scene(&["a.jpg", "img_1.5", "c.exr"], ""));
    accepted_in(&scratch, &["render", "s.xml", "-q"]);
    let jpeg = std::fs::read(scratch.path("a.jpg")).unwrap();
    assert_eq!(jpeg[..3], [0xFF, 0xD8, 0xFF], "a.jpg is a JPEG");
    for file in ["a.exr", "img_1.5.png", "img_1.5.exr", "c.exr", "c.png"] {
        assert!(scratch.path(file).is_file(), "{file} missing");
    }
}

/// Two facing mirrors and a MaxRecursionDepth of 2000: a recursive integrator overflowed
/// its thread's stack here (SIGABRT).
#[test]
fn deep_recursion_between_mirrors_does_not_overflow_the_stack() {
    let scratch = Scratch::new();
    let text = crate::scenes::mirror_box_xml(2000);
    scratch.write("mirrors.xml", text);
    accepted_in(&scratch, &["render", "mirrors.xml", "-q", "--threads", "2"]);
    assert!(scratch.path("mirrors.png").is_file());
}

refused_cases! {
    num_samples_a_megabyte_long: ["s.xml" => xml_scene(&["a.png"], "").replace("<ImageName>", &format!("<NumSamples>{}</NumSamples><ImageName>", "9".repeat(1_000_000)))], ["render", "s.xml"]
        => ["s.xml", "NumSamples", "characters cut", "(line 12)"];
    undefined_transformation_a_megabyte_long: ["s.xml" => xml_scene(&["a.png"], "").replace("<Radius>1</Radius>", &format!("<Radius>1</Radius><Transformations>t{}</Transformations>", "1".repeat(1_000_000)))], ["render", "s.xml"]
        => ["s.xml", "characters cut"];
}

// The reader looked attributes up by name: a misspelt or unknown one was ignored without a
// word, and a second vertex list shifted every index after the first.
refused_cases! {
    attribute_unknown_on_a_camera: ["s.xml" => xml_scene(&["a.png"], "").replace("<Camera id=\"1\">", "<Camera id=\"1\" foo=\"bar\">")], ["render", "s.xml"]
        => ["s.xml", "unknown attribute foo=\"bar\"", "<Camera> takes: id, type, handedness", "(line 5)"];
    attribute_misspelt_on_faces: ["s.xml" => xml_scene(&["a.png"], "").replace("<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere>", "<Mesh id=\"1\"><Material>1</Material><Faces vertexOfset=\"2\">1 1 1</Faces></Mesh>")], ["render", "s.xml"]
        => ["s.xml", "unknown attribute vertexOfset=\"2\"", "vertexOffset", "(line 28)"];
    attribute_on_an_element_that_takes_none: ["s.xml" => xml_scene(&["a.png"], "").replace("<Radius>1</Radius>", "<Radius scale=\"2\">1</Radius>")], ["render", "s.xml"]
        => ["s.xml", "unknown attribute scale=\"2\"", "<Radius> takes: none", "(line 28)"];
    vertex_data_given_twice: ["s.xml" => xml_scene(&["a.png"], "").replace("<VertexData>0 0 -3</VertexData>", "<VertexData>0 0 -3</VertexData>\n  <VertexData>1 1 1</VertexData>")], ["render", "s.xml"]
        => ["s.xml", "<VertexData> is given more than once", "(line 27)"];
}

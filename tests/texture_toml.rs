//! Image textures and normal maps from the TOML format: a quad seen face-on shows its image,
//! a flat normal map changes nothing and a tilted one changes the shading, on every backend.

mod common;

use common::command::temp_dir;
use common::*;
use embray::choice::Choice;
use std::path::Path;

fn write_png(path: &Path, width: u32, height: u32, texel: impl Fn(u32, u32) -> [u8; 3]) {
    let image = image::RgbImage::from_fn(width, height, |x, y| image::Rgb(texel(x, y)));
    image.save(path).unwrap();
}

/// A unit quad facing the camera, lit by a point light at the camera, with `material`.
fn quad_scene(dir: &Path, material: &str) -> embray::scene::SceneDesc {
    let text = format!(
        r#"
[camera]
lookfrom = [0.5, 0.5, 2.0]
lookat = [0.5, 0.5, 0.0]
vfov = 28.0
resolution = [32, 32]

[render]
integrator = "path"
max_depth = 1

[materials.m]
{material}

[[objects]]
type = "quad"
material = "m"
corner = [0.0, 0.0, 0.0]
u = [1.0, 0.0, 0.0]
v = [0.0, 1.0, 0.0]

[[lights]]
type = "point"
position = [0.5, 0.5, 2.0]
intensity = [4.0, 4.0, 4.0]
"#
    );
    embray::scene::load_str(&text, &dir.join("scene.toml")).expect("scene loads")
}

#[test]
fn an_image_texture_shows_on_its_quad_and_normal_maps_bend_the_shading() {
    let dir = temp_dir("texture-toml");
    // Four vertical stripes: red, grey, red, grey.
    write_png(&dir.join("stripes.png"), 8, 2, |x, _| {
        if (x / 2) % 2 == 0 { [220, 30, 30] } else { [160, 160, 160] }
    });
    write_png(&dir.join("flat.png"), 2, 2, |_, _| [128, 128, 255]);
    write_png(&dir.join("tilted.png"), 2, 2, |_, _| [230, 128, 180]);
    // Heights: constant, and a ramp rising along u.
    write_png(&dir.join("level.png"), 4, 4, |_, _| [90, 90, 90]);
    write_png(&dir.join("ramp.png"), 64, 4, |x, _| [(x * 4) as u8; 3]);
    let image = r#"texture = { type = "image", file = "stripes.png", interpolation = "nearest" }"#;
    for backend in backends() {
        let render = |material: &str| {
            let scene = quad_scene(&dir, material);
            render_ok(&scene, &options(&scene, backend, 4)).film
        };
        let textured = render(image);
        // Along the middle row the stripes alternate: count the changes of the dominant
        // colour (the quad spans the whole row).
        let row: Vec<bool> = (0..32)
            .map(|x| {
                let c = textured.color[16 * 32 + x];
                c.x > 2.0 * c.y
            })
            .collect();
        let changes = row.windows(2).filter(|w| w[0] != w[1]).count();
        assert_eq!(changes, 3, "{}: stripes along the row: {row:?}", backend.name());
        // The image's top row is v = 0, the quad's v grows upwards: the image is upright,
        // not mirrored left to right (the leftmost stripe is red).
        assert!(row[1], "{}: the leftmost stripe must be red", backend.name());

        let flat =
            render(&format!("{image}\nnormal_map = {{ type = \"image\", file = \"flat.png\" }}"));
        let tilted =
            render(&format!("{image}\nnormal_map = {{ type = \"image\", file = \"tilted.png\" }}"));
        let flat_error = image_error(&flat, &textured);
        assert!(
            flat_error.max_abs < 0.02,
            "{}: a flat normal map changed the image: {flat_error:?}",
            backend.name()
        );
        let luminance =
            |f: &embray::film::Film| f.color.iter().map(|c| c.element_sum() as f64).sum::<f64>();
        // Normals tilted ~45° away from the light at the camera: less light.
        let ratio = luminance(&tilted) / luminance(&textured);
        assert!(ratio < 0.85 && ratio > 0.3, "{}: tilted / flat = {ratio}", backend.name());

        // A level height field changes nothing; a ramp tilts the normal away from the light.
        let bump = |file: &str| {
            render(&format!(
                "{image}\nbump_map = {{ type = \"image\", file = \"{file}\", factor = 1.0 }}"
            ))
        };
        let level = image_error(&bump("level.png"), &textured);
        assert!(
            level.max_abs < 0.02,
            "{}: a level bump map changed the image: {level:?}",
            backend.name()
        );
        let ratio = luminance(&bump("ramp.png")) / luminance(&textured);
        assert!(ratio < 0.95 && ratio > 0.3, "{}: ramp / flat = {ratio}", backend.name());
    }
}

/// An empty scene of `resolution` whose `[render]` table holds `render`.
fn backdrop_scene(dir: &Path, resolution: [u32; 2], render: &str) -> embray::scene::SceneDesc {
    let text = format!(
        r#"
[camera]
lookfrom = [0.0, 0.0, 2.0]
lookat = [0.0, 0.0, 0.0]
vfov = 30.0
resolution = [{}, {}]

[render]
max_depth = 2
background = [0.5, 0.5, 0.5]
{render}

[materials.grey]
albedo = [0.5, 0.5, 0.5]

[[objects]]
type = "sphere"
material = "grey"
center = [0.0, 0.0, -50.0]
radius = 1.0
"#,
        resolution[0], resolution[1]
    );
    embray::scene::load_str(&text, &dir.join("scene.toml")).expect("scene loads")
}

#[test]
fn a_background_texture_is_seen_texel_for_texel_behind_the_scene() {
    let dir = common::command::temp_dir("texture-toml-backdrop");
    let texel = |x: u32, y: u32| [(x * 20) as u8, (y * 30) as u8, ((x + y) * 9) as u8];
    write_png(&dir.join("backdrop.png"), 12, 8, texel);
    let render = "background_texture = { type = \"image\", file = \"backdrop.png\", \
                  interpolation = \"bilinear\", encoding = \"raw\", normalizer = 255 }";
    let scene = backdrop_scene(&dir, [12, 8], render);
    for integrator in [embray::scene::IntegratorKind::Path, embray::scene::IntegratorKind::Whitted]
    {
        for backend in backends() {
            let mut options = options(&scene, backend, 4);
            options.integrator = integrator;
            let film = render_ok(&scene, &options).film;
            for y in 0..8 {
                for x in 0..12 {
                    if (5..7).contains(&x) && (3..5).contains(&y) {
                        continue; // the far sphere, at the centre
                    }
                    let expected = glam::Vec3::from_array(texel(x, y).map(|c| c as f32 / 255.0));
                    // Jittered samples blend neighbours bilinearly; the mean stays close.
                    let got = film.pixel(x, y);
                    assert!(
                        (got - expected).abs().max_element() < 0.06,
                        "{integrator:?} {backend:?} ({x}, {y}): {got} vs {expected}"
                    );
                }
            }
        }
    }
    // Pixel centres sample texel centres exactly: at 1 spp without jitter, equality.
    let mut options = options(&scene, embray::accel::BackendKind::default_compiled(), 1);
    options.jitter = false;
    let film = render_ok(&scene, &options).film;
    let expected = glam::Vec3::from_array(texel(2, 1).map(|c| c as f32 / 255.0));
    assert!((film.pixel(2, 1) - expected).abs().max_element() < 1e-6);
    // The TOML round trip keeps it.
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    writer.write(&scene, &dir.join("back.toml"), "round trip").unwrap();
    let back = embray::scene::load(&dir.join("back.toml")).unwrap();
    assert_eq!(back.settings, scene.settings);
    // Solid patterns have no place on the image plane.
    let err = embray::scene::load_str(
        "[camera]\nlookfrom = [0, 0, 2]\nlookat = [0, 0, 0]\nvfov = 30\nresolution = [4, 4]\n\n[render]\n\
         background_texture = { type = \"perlin\", scale = 2 }\n",
        &dir.join("bad.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("render.background_texture.type is perlin")
            && err.contains("image or checker2d"),
        "{err}"
    );
}

#[test]
fn pixel_aspect_stretches_the_horizontal_field_of_view() {
    let dir = common::command::temp_dir("texture-toml-pixel-aspect");
    let square = backdrop_scene(&dir, [16, 8], "");
    let mut stretched = square.clone();
    stretched.camera.pixel_aspect = 0.5;
    let camera = |scene: &embray::scene::SceneDesc| {
        embray::compile::to_render_scene(
            scene,
            embray::render_space::RenderSpace::Cameraworld,
            embray::compile::EffectsMode::Auto,
        )
        .unwrap()
        .camera
    };
    // The right edge's ray: at half the pixel aspect it is half as far off the axis.
    let edge = glam::Vec2::new(16.0, 4.0);
    let (a, b) =
        (camera(&square).generate_ray(edge, None), camera(&stretched).generate_ray(edge, None));
    let slope = |d: glam::Vec3| d.x / -d.z;
    assert!(
        (slope(b.dir) - 0.5 * slope(a.dir)).abs() < 1e-6,
        "{} vs {}",
        slope(b.dir),
        slope(a.dir)
    );
    let toml = "[camera]\nlookfrom = [0, 0, 2]\nlookat = [0, 0, 0]\nvfov = 30\nresolution = [4, 4]\npixel_aspect = 0\n";
    let err = embray::scene::load_str(toml, &dir.join("bad.toml")).unwrap_err().to_string();
    assert!(err.contains("camera.pixel_aspect is 0, but must be between 0.001 and 1000"), "{err}");
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    writer.write(&stretched, &dir.join("back.toml"), "round trip").unwrap();
    assert_eq!(embray::scene::load(&dir.join("back.toml")).unwrap().camera, stretched.camera);
}

/// The path tracer's course lobe takes its reflectance from `specular_texture` where given:
/// a constant texture of ks renders exactly as `phong.specular = ks`, and both add a
/// highlight to the lobe-less quad.
#[test]
fn a_specular_texture_drives_the_path_tracers_course_lobe() {
    let dir = temp_dir("specular-toml");
    let base = "albedo = [0.3, 0.3, 0.3]\nbrdf = { model = \"modified_phong\", normalized = true }";
    for backend in backends() {
        let render = |material: String| {
            let scene = quad_scene(&dir, &material);
            render_ok(&scene, &options(&scene, backend, 4)).film
        };
        let given =
            render(format!("{base}\nphong = {{ specular = [0.5, 0.5, 0.5], exponent = 20 }}"));
        let textured = render(format!(
            "{base}\nphong = {{ specular = [0, 0, 0], exponent = 20 }}\n\
             specular_texture = {{ type = \"checker2d\", scale = 1, even = [0.5, 0.5, 0.5], \
             odd = [0.5, 0.5, 0.5] }}"
        ));
        let matte = render(format!("{base}\nphong = {{ specular = [0, 0, 0], exponent = 20 }}"));
        let same = image_error(&textured, &given);
        assert!(same.max_abs < 1e-6, "{}: {same:?}", backend.name());
        let sum =
            |f: &embray::film::Film| f.color.iter().map(|c| c.element_sum() as f64).sum::<f64>();
        let ratio = sum(&given) / sum(&matte);
        assert!(ratio > 1.05, "{}: the lobe adds only {ratio}", backend.name());
    }
}

/// A unit quad in an OBJ whose MTL material paints it with `map_Kd`, OBJ texture coordinates
/// (v up), seen face on.
fn obj_with_map_kd(dir: &Path, map_kd: &str) -> Result<embray::scene::SceneDesc, String> {
    std::fs::write(
        dir.join("quad.obj"),
        "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl painted\nf 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    std::fs::write(dir.join("quad.mtl"), format!("newmtl painted\nKd 0.5 0.5 0.5\n{map_kd}\n"))
        .unwrap();
    let text = r#"
[camera]
lookfrom = [0.5, 0.5, 2.0]
lookat = [0.5, 0.5, 0.0]
vfov = 20.0
resolution = [8, 8]

[[objects]]
type = "mesh"
file = "quad.obj"

[[lights]]
type = "point"
position = [0.5, 0.5, 2.0]
intensity = [4.0, 4.0, 4.0]
"#;
    embray::scene::load_str(text, &dir.join("scene.toml")).map_err(|e| e.to_string())
}

#[test]
fn an_mtl_map_kd_paints_its_mesh_the_right_way_up() {
    let dir = temp_dir("texture-mtl");
    // The image's top half red, its bottom half blue.
    write_png(
        &dir.join("paint.png"),
        2,
        8,
        |_, y| if y < 4 { [230, 20, 20] } else { [20, 20, 230] },
    );
    let scene = obj_with_map_kd(&dir, "map_Kd paint.png").unwrap();
    let mut options = options(&scene, embray::accel::BackendKind::default_compiled(), 1);
    options.first_hit_albedo = true;
    let film = render_ok(&scene, &options).film;
    // The top of the quad (v = 1) shows the image's top row.
    let (top, bottom) = (film.albedo[film.index(4, 1)], film.albedo[film.index(4, 6)]);
    assert!(top.x > 0.5 && top.z < 0.05, "top {top}");
    assert!(bottom.z > 0.5 && bottom.x < 0.05, "bottom {bottom}");
    // The TOML writer keeps it (the image named with flip_v).
    let mut writer = embray::scene::toml_writer::TomlWriter::new(dir.join("meshes"));
    writer.write(&scene, &dir.join("back.toml"), "round trip").unwrap();
    assert!(std::fs::read_to_string(dir.join("back.toml")).unwrap().contains("flip_v = true"));
    let back = embray::scene::load(&dir.join("back.toml")).unwrap();
    let texture = |s: &embray::scene::SceneDesc| s.materials.iter().find_map(|m| m.texture.clone());
    assert_eq!(texture(&back), texture(&scene));
    // A missing image names itself, the MTL file, its line and the material.
    let err = obj_with_map_kd(&dir, "map_Kd -s 2 2 1 gone.png").unwrap_err();
    for part in ["gone.png", "quad.mtl", "line 3", "map_Kd of material 'painted'"] {
        assert!(err.contains(part), "'{part}' not in: {err}");
    }
}

/// A `mesh_attribute` texture shows a PLY file's face colours (each triangle of a polygon
/// its polygon's), and a shape without the attribute is refused with the field's line.
#[test]
fn mesh_attributes_colour_their_faces_and_a_missing_one_is_refused() {
    let dir = temp_dir("mesh-attribute-toml");
    // Two quads side by side: red on the left, blue on the right.
    let ply = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n\
        property float z\nelement face 2\nproperty list uchar int vertex_indices\n\
        property float color_0\nproperty float color_1\nproperty float color_2\nend_header\n\
        0 0 0\n0.5 0 0\n1 0 0\n0 1 0\n0.5 1 0\n1 1 0\n\
        4 0 1 4 3 0.8 0.1 0.1\n4 1 2 5 4 0.1 0.1 0.8\n";
    std::fs::write(dir.join("halves.ply"), ply).unwrap();
    let scene = |object: &str| {
        format!(
            "[camera]\nlookfrom = [0.5, 0.5, 2.0]\nlookat = [0.5, 0.5, 0.0]\nvfov = 28.0\n\
             resolution = [16, 16]\n\n[render]\nmax_depth = 1\n\n[materials.m]\n\
             texture = {{ type = \"mesh_attribute\", name = \"face_color\" }}\n\n\
             [[objects]]\n{object}\nmaterial = \"m\"\n\n[[lights]]\ntype = \"point\"\n\
             position = [0.5, 0.5, 2.0]\nintensity = [4.0, 4.0, 4.0]\n"
        )
    };
    let text = scene("type = \"mesh\"\nfile = \"halves.ply\"");
    let desc = embray::scene::load_str(&text, &dir.join("scene.toml")).expect("scene loads");
    for backend in backends() {
        let film = render_ok(&desc, &options(&desc, backend, 4)).film;
        let (left, right) = (film.color[8 * 16 + 4], film.color[8 * 16 + 11]);
        assert!(left.x > 4.0 * left.z && right.z > 4.0 * right.x, "{backend:?}: {left} {right}");
    }
    let text = scene("type = \"sphere\"\ncenter = [0.5, 0.5, 0.0]\nradius = 0.3");
    let message = embray::scene::load_str(&text, &dir.join("scene.toml")).unwrap_err().to_string();
    for part in ["objects[0].material", "mesh attribute `face_color`", "it has: none", "line"] {
        assert!(message.contains(part), "{message}");
    }
}

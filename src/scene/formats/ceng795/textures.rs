//! `<Textures>` (hw4): `<Images>` and `<TextureMap>`s, and an object's `<Textures>` list →
//! the object's own copy of its material with the textures attached.
//!
//! Image texels keep the file's 0–255 values (a 16-bit file's scaled to them) and are
//! divided by `Normalizer` (default 255, the text's "divide the texture color value by
//! 255"); `Interpolation` defaults to nearest (the normal-map scenes give none, and match
//! their references 99.98 % with nearest, 83 % with bilinear); Perlin noise (`NoiseScale`,
//! `NoiseConversion`) and the checkerboard (`Scale`, `Offset`, `BlackColor`, `WhiteColor`)
//! are evaluated at the object-space point. Decal modes: `replace_kd`, `blend_kd`,
//! `replace_all` set the diffuse texture, `replace_ks` the specular one, `replace_normal`
//! the normal map, `bump_normal` the bump map; `replace_background` makes an image the
//! scene's backdrop (`RenderSettings::background_texture`).

use super::xml::{Xml, describe, id_list, tokens};
use crate::choice::Choice;
use crate::excerpt::excerpt;
use crate::scene::desc::{
    Interpolation, MaterialDesc, NoiseConversion, Pattern, TextureDesc, TextureImage, TextureMode,
};
use crate::scene::error::SceneError;
use crate::scene::texture_image::{ImageRef, load_radiance};
use glam::DAffine3;
use roxmltree::Node;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// What a texture map does to the objects that list it.
#[derive(Clone, Debug)]
enum Role {
    Diffuse(TextureMode),
    Specular,
    Normal,
    Bump(f32),
    /// The scene's backdrop (replace_background).
    Background,
}

struct TextureMap {
    role: Role,
    pattern: MapPattern,
}

/// A map's pattern; an image map's image is decoded when an object first lists the map, so
/// that a scene's unused maps are never read (as Mitsuba skips unused bitmaps).
enum MapPattern {
    Ready(Pattern),
    Image {
        source: ImageSource,
        decoded: std::cell::OnceCell<Arc<TextureImage>>,
        interpolation: Interpolation,
        normalizer: f32,
    },
}

impl MapPattern {
    /// The pattern, an image map's image decoded the first time.
    fn pattern(&self, x: &Xml) -> Result<Pattern, SceneError> {
        let (source, decoded, interpolation, normalizer) = match self {
            MapPattern::Ready(pattern) => return Ok(pattern.clone()),
            MapPattern::Image { source, decoded, interpolation, normalizer } => {
                (source, decoded, interpolation, normalizer)
            }
        };
        let image = match decoded.get() {
            Some(image) => Arc::clone(image),
            None => {
                let at = source.at(x);
                let image = load_radiance(&at, false)?;
                Arc::clone(decoded.get_or_init(|| image))
            }
        };
        Ok(Pattern::Image { image, interpolation: *interpolation, normalizer: *normalizer })
    }
}

/// An `<Image>` element: where its file is and how to name it in messages.
#[derive(Clone)]
struct ImageSource {
    path: std::path::PathBuf,
    item: String,
    line: crate::scene::error::Line,
}

/// The file's texture maps and images by id.
#[derive(Default)]
pub(super) struct TextureMaps {
    maps: HashMap<String, TextureMap>,
    images: HashMap<String, ImageSource>,
    /// The replace_background map, in display units (0–255, as BackgroundColor).
    pub background: Option<TextureDesc>,
}

const MAP_CHILDREN: [&str; 11] = [
    "ImageId",
    "DecalMode",
    "Interpolation",
    "Normalizer",
    "BumpFactor",
    "NoiseScale",
    "NoiseConversion",
    "Scale",
    "Offset",
    "BlackColor",
    "WhiteColor",
];

fn parse_choice<T: Choice>(x: &Xml, node: Node) -> Result<T, SceneError> {
    T::from_name(x.text(node)).map_err(|e| x.error(node, e.to_string()))
}

/// Every `<Textures>` element of the scene.
pub(super) fn texture_maps<'a, 'i: 'a>(
    x: &Xml,
    base_dir: &Path,
    lists: impl Iterator<Item = Node<'a, 'i>>,
) -> Result<TextureMaps, SceneError> {
    let mut image_sources: HashMap<String, ImageSource> = HashMap::new();
    let mut map_nodes = Vec::new();
    for list in lists {
        x.check_children(list, &["Images", "TextureMap"])?;
        for child in list.children().filter(Node::is_element) {
            if child.has_tag_name("TextureMap") {
                map_nodes.push(child);
                continue;
            }
            x.check_children(child, &["Image"])?;
            for image in child.children().filter(Node::is_element) {
                let id = image.attribute("id").map(str::trim).unwrap_or("").to_owned();
                let source = ImageSource {
                    path: base_dir.join(x.text(image)),
                    item: describe(image),
                    line: x.line(image),
                };
                if image_sources.insert(id.clone(), source).is_some() {
                    return Err(
                        x.error(image, format!("image id {} is defined twice", excerpt(&id)))
                    );
                }
            }
        }
    }
    let mut maps = HashMap::new();
    let mut background = None;
    for node in map_nodes {
        x.check_children(node, &MAP_CHILDREN)?;
        let id = node.attribute("id").map(str::trim).unwrap_or("").to_owned();
        let decal = x.required(node, "DecalMode")?;
        let role = match x.text(decal) {
            "replace_kd" => Role::Diffuse(TextureMode::Replace),
            "blend_kd" => Role::Diffuse(TextureMode::Blend),
            "replace_all" => Role::Diffuse(TextureMode::ReplaceAll),
            "replace_ks" => Role::Specular,
            "replace_normal" => Role::Normal,
            "bump_normal" => Role::Bump(match x.child(node, "BumpFactor")? {
                Some(n) => {
                    let v = x.scalar(n)?;
                    if !(v as f32).is_finite() {
                        return Err(x.out_of_range(n, v, "small enough for f32"));
                    }
                    v as f32
                }
                None => 1.0,
            }),
            "replace_background" => Role::Background,
            other => {
                return Err(x.error(
                    decal,
                    format!(
                        "unknown DecalMode {} (expected replace_kd, blend_kd, replace_ks, \
                         replace_all, replace_normal, bump_normal or replace_background)",
                        excerpt(other)
                    ),
                ));
            }
        };
        let positive = |name: &str, default: f64| -> Result<f32, SceneError> {
            match x.child(node, name)? {
                None => Ok(default as f32),
                Some(n) => {
                    let v = x.scalar(n)?;
                    if !(v > 0.0) || !(v as f32).is_finite() {
                        return Err(x.out_of_range(n, v, "> 0 (and small enough for f32)"));
                    }
                    Ok(v as f32)
                }
            }
        };
        let pattern = match node.attribute("type").map(str::trim) {
            Some("image") => {
                let image_id_node = x.required(node, "ImageId")?;
                let source = image_source(x, &image_sources, image_id_node)?.clone();
                let interpolation = match x.child(node, "Interpolation")? {
                    Some(n) => parse_choice::<Interpolation>(x, n)?,
                    None => Interpolation::Nearest,
                };
                let normalizer = positive("Normalizer", 255.0)?;
                let decoded = std::cell::OnceCell::new();
                MapPattern::Image { source, decoded, interpolation, normalizer }
            }
            Some("perlin") => MapPattern::Ready(Pattern::Perlin {
                scale: positive("NoiseScale", 1.0)?,
                conversion: match x.child(node, "NoiseConversion")? {
                    Some(n) => parse_choice::<NoiseConversion>(x, n)?,
                    None => NoiseConversion::Absolute,
                },
            }),
            Some("checkerboard") => {
                let color = |name: &str, default: f32| match x.child(node, name)? {
                    Some(n) => x.color(n),
                    None => Ok(glam::Vec3::splat(default)),
                };
                let offset = match x.child(node, "Offset")? {
                    Some(n) => x.scalar(n)? as f32,
                    None => 0.0,
                };
                MapPattern::Ready(Pattern::CourseChecker {
                    scale: positive("Scale", 1.0)?,
                    offset,
                    black: color("BlackColor", 0.0)?,
                    white: color("WhiteColor", 1.0)?,
                })
            }
            other => {
                return Err(x.error(
                    node,
                    format!(
                        "texture map type {} is not supported (expected image, perlin or \
                         checkerboard)",
                        excerpt(other.unwrap_or("(none)"))
                    ),
                ));
            }
        };
        if matches!(role, Role::Background) {
            let Pattern::Image { image, interpolation, normalizer } = &pattern.pattern(x)? else {
                return Err(x.error(node, "a replace_background texture map must be an image"));
            };
            if background.is_some() {
                return Err(x.error(node, "a scene takes one replace_background texture map"));
            }
            // The backdrop is seen as it is: texels / Normalizer in BackgroundColor's units.
            background = Some(TextureDesc {
                pattern: Pattern::Image {
                    image: Arc::clone(image),
                    interpolation: *interpolation,
                    normalizer: normalizer / 255.0,
                },
                mode: TextureMode::Replace,
                texture_from_object: DAffine3::IDENTITY,
            });
        }
        if maps.insert(id.clone(), TextureMap { role, pattern }).is_some() {
            return Err(x.error(node, format!("texture map id {} is defined twice", excerpt(&id))));
        }
    }
    Ok(TextureMaps { maps, images: image_sources, background })
}

/// The image `id_node` (an `<ImageId>`) names.
fn image_source<'s>(
    x: &Xml,
    images: &'s HashMap<String, ImageSource>,
    id_node: Node,
) -> Result<&'s ImageSource, SceneError> {
    let id = x.text(id_node);
    let Some(source) = images.get(id) else {
        return Err(x.error(
            id_node,
            format!("image id {} is not defined; images: {}", excerpt(id), id_list(images.keys())),
        ));
    };
    Ok(source)
}

impl ImageSource {
    /// Where the image is named, for the loader's messages.
    fn at<'x>(&self, x: &'x Xml) -> ImageRef<'x> {
        ImageRef {
            image: self.path.clone(),
            scene: x.file,
            item: self.item.clone(),
            line: self.line,
        }
    }
}

impl TextureMaps {
    /// The radiance map `id_node` (an `<ImageId>`) names: an EXR's linear values, or a
    /// PNG/JPEG's 0–255 values as textures keep them.
    pub fn radiance_map(&self, x: &Xml, id_node: Node) -> Result<Arc<TextureImage>, SceneError> {
        load_radiance(&image_source(x, &self.images, id_node)?.at(x), false)
    }

    /// `material` with the texture maps listed in `node`'s `<Textures>` elements attached,
    /// or `None` if it lists none.
    pub fn textured(
        &self,
        x: &Xml,
        node: Node,
        material: &MaterialDesc,
    ) -> Result<Option<MaterialDesc>, SceneError> {
        let mut textured = material.clone();
        let mut listed = false;
        for list in node.children().filter(|c| c.has_tag_name("Textures")) {
            for (id, pos) in tokens(list) {
                listed = true;
                let Some(map) = self.maps.get(id) else {
                    let ids = id_list(self.maps.keys());
                    return Err(x.token_error(
                        list,
                        pos,
                        format!(
                            "texture map id {} is not defined; texture maps: {ids}",
                            excerpt(id)
                        ),
                    ));
                };
                let (slot, mode, kind) = match map.role {
                    Role::Diffuse(mode) => (&mut textured.texture, mode, "diffuse"),
                    Role::Specular => {
                        (&mut textured.specular_texture, TextureMode::Replace, "specular")
                    }
                    Role::Normal => (&mut textured.normal_map, TextureMode::Replace, "normal-map"),
                    Role::Background => {
                        return Err(x.token_error(
                            list,
                            pos,
                            format!(
                                "texture map {} is the scene's background (replace_background), \
                                 not an object's texture",
                                excerpt(id)
                            ),
                        ));
                    }
                    Role::Bump(factor) => {
                        if textured.bump_map.is_some() {
                            return Err(x.token_error(
                                list,
                                pos,
                                format!(
                                    "texture map {} is the object's second bump map",
                                    excerpt(id)
                                ),
                            ));
                        }
                        textured.bump_map = Some(crate::scene::desc::BumpMapDesc {
                            texture: TextureDesc {
                                pattern: map.pattern.pattern(x)?,
                                mode: TextureMode::Replace,
                                texture_from_object: DAffine3::IDENTITY,
                            },
                            factor,
                            scale: crate::scene::desc::BumpScale::CourseTexels,
                        });
                        continue;
                    }
                };
                if slot.is_some() {
                    return Err(x.token_error(
                        list,
                        pos,
                        format!(
                            "texture map {} is the object's second {} texture",
                            excerpt(id),
                            kind
                        ),
                    ));
                }
                *slot = Some(TextureDesc {
                    pattern: map.pattern.pattern(x)?,
                    mode,
                    texture_from_object: DAffine3::IDENTITY,
                });
            }
        }
        if listed {
            textured.name = format!("{} textured ({})", material.name, describe(node));
        }
        Ok(listed.then_some(textured))
    }
}

//! The attributes each element of the course's XML takes. The reader looks up the ones it
//! knows by name, so any other (a misspelt `vertexOfset`, a stray `foo`) would be ignored
//! without a word: every element's attributes are checked against this table first. It
//! lists what the reader reads, which covers every attribute of the course's scenes (2021
//! and 2022 homeworks) and its instructions.

use super::xml::Xml;
use crate::scene::error::SceneError;
use roxmltree::Node;

/// Elements that take only an `id`.
const ID_ONLY: [&str; 15] = [
    "AmbientLight",
    "PointLight",
    "AreaLight",
    "DirectionalLight",
    "SpotLight",
    "LightSphere",
    "Sphere",
    "Triangle",
    "Translation",
    "Scaling",
    "Rotation",
    "Composite",
    "Image",
    "OriginalBlinnPhong",
    "OriginalPhong",
];

/// Elements of the format that take no attribute: their values are their text. An element
/// of no list is left to its parent's check, which names it as unsupported.
const NO_ATTRIBUTES: [&str; 65] = [
    "Scene",
    "BackgroundColor",
    "ShadowRayEpsilon",
    "IntersectionTestEpsilon",
    "MaxRecursionDepth",
    "Cameras",
    "Lights",
    "BRDFs",
    "Materials",
    "Transformations",
    "Textures",
    "Objects",
    "Images",
    "Position",
    "Gaze",
    "GazePoint",
    "Up",
    "NearPlane",
    "NearDistance",
    "FovY",
    "FocusDistance",
    "ApertureSize",
    "ImageResolution",
    "ImageName",
    "NumSamples",
    "Tonemap",
    "TMO",
    "TMOOptions",
    "Saturation",
    "Gamma",
    "Renderer",
    "RendererParams",
    "Intensity",
    "Radiance",
    "Normal",
    "Size",
    "Direction",
    "CoverageAngle",
    "FalloffAngle",
    "ImageId",
    "AmbientReflectance",
    "DiffuseReflectance",
    "SpecularReflectance",
    "MirrorReflectance",
    "PhongExponent",
    "RefractionIndex",
    "AbsorptionCoefficient",
    "AbsorptionIndex",
    "Roughness",
    "Transparency",
    "Exponent",
    "Indices",
    "Center",
    "Radius",
    "MotionBlur",
    "Scale",
    "Offset",
    "DecalMode",
    "Interpolation",
    "Normalizer",
    "BumpFactor",
    "NoiseScale",
    "NoiseConversion",
    "BlackColor",
    "WhiteColor",
];

/// The attributes `element` takes; `None` for an element the format does not have.
fn known(element: &str) -> Option<&'static [&'static str]> {
    Some(match element {
        "Camera" => &["id", "type", "handedness"],
        "Mesh" | "LightMesh" => &["id", "shadingMode"],
        "Faces" => &["plyFile", "vertexOffset", "textureOffset"],
        "MeshInstance" => &["id", "baseMeshId", "resetTransform"],
        "Material" => &["id", "type", "BRDF", "degamma"],
        "TextureMap" => &["id", "type"],
        "SphericalDirectionalLight" => &["id", "type"],
        "ModifiedBlinnPhong" | "ModifiedPhong" => &["id", "normalized"],
        "TorranceSparrow" => &["id", "kdfresnel"],
        // Read to say that a binary file cannot be.
        "VertexData" | "TexCoordData" => &["binaryFile"],
        other if ID_ONLY.contains(&other) => &["id"],
        other if NO_ATTRIBUTES.contains(&other) => &[],
        _ => return None,
    })
}

/// Refuses the first attribute in the document that its element does not take.
pub(super) fn check_attributes(x: &Xml, root: Node) -> Result<(), SceneError> {
    for node in root.descendants().filter(Node::is_element) {
        let element = node.tag_name().name();
        let Some(allowed) = known(element) else { continue };
        let unknown =
            node.attributes().find(|a| a.namespace().is_some() || !allowed.contains(&a.name()));
        if let Some(attribute) = unknown {
            let takes = match allowed {
                [] => "none".to_owned(),
                names => names.join(", "),
            };
            let problem = format!(
                "unknown attribute {}=\"{}\" (<{element}> takes: {takes})",
                crate::excerpt::excerpt(attribute.name()),
                crate::excerpt::excerpt(attribute.value())
            );
            return Err(x.token_error(node, attribute.range().start, problem));
        }
    }
    Ok(())
}

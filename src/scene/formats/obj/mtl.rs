//! An OBJ's MTL material → a `MaterialDesc`, made only when a scene uses the MTL materials
//! (a scene that gives the object its own material reads no MTL statement, and is told of
//! none): its statements read (`mtl_material`), mapped (`mtl_mapping`), its images loaded
//! (`mtl_texture`), what is not understood gathered in `MtlNotes`.

use super::ObjRef;
use super::mtl_mapping::Lobe;
use super::mtl_material::{Given, Problem, Statement, statements};
use super::mtl_notes::{MtlNotes, Note};
use super::mtl_texture::{MapAt, MapStatement, colour, data, looks_like_normal_map};
use crate::scene::desc::{BumpMapDesc, BumpScale, MaterialDesc, Opacity};
use crate::scene::error::{Line, SceneError};
use glam::Vec3;
use std::path::PathBuf;
use std::sync::Arc;

/// A material of an OBJ's MTL file: where it is defined.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ObjMaterial {
    pub name: String,
    pub mtl: PathBuf,
    /// The MTL file's text (shared by its materials).
    pub text: Arc<str>,
    /// The line (from 1) of its `newmtl`, and where that line begins in `text`.
    pub line: usize,
    pub offset: usize,
}

/// The lines (from 1) of the `newmtl` statements of an MTL text, and the byte offsets where
/// they begin: one per material, in the order tobj reads them.
pub(super) fn newmtl_lines(text: &str) -> Vec<(usize, usize)> {
    let newmtl = |line: &str| line.split_whitespace().next() == Some("newmtl");
    let mut offset = 0;
    let mut found = Vec::new();
    for (i, line) in text.split_inclusive('\n').enumerate() {
        if newmtl(line) {
            found.push((i + 1, offset));
        }
        offset += line.len();
    }
    found
}

/// The scene material `m` describes (named by the caller); notes go to `notes`, bad values
/// are errors naming the MTL file, the material and the line.
pub(crate) fn material_desc(
    m: &ObjMaterial,
    obj_ref: &ObjRef,
    notes: &mut MtlNotes,
) -> Result<MaterialDesc, SceneError> {
    let error = |(line, problem): Problem| {
        let problem = format!("material '{}': {problem}", crate::excerpt::excerpt(&m.name));
        obj_ref.error(&m.mtl, problem, Line(Some(line)))
    };
    let statements = statements(&m.text, m.line, m.offset);
    let mut own = Vec::new();
    let given = Given::read(&statements, &mut own).map_err(error)?;
    let (mut material, lobe) = given.material(&mut own).map_err(error)?;
    let result =
        Textures { given: &given, m, notes: &mut own, error: &error }.apply(lobe, &mut material);
    own.sort_by_key(|note| note.line);
    for note in own {
        notes.add(&m.mtl, &m.name, note);
    }
    result.map(|()| material)
}

struct Textures<'a, 'g, E: Fn(Problem) -> SceneError> {
    given: &'a Given<'g>,
    m: &'a ObjMaterial,
    notes: &'a mut Vec<Note>,
    error: &'a E,
}

impl<E: Fn(Problem) -> SceneError> Textures<'_, '_, E> {
    fn note(&mut self, line: usize, message: impl Into<String>) {
        self.notes.push(Note::new(line, message));
    }

    fn at<'s>(&'s self, st: &Statement<'s>) -> MapAt<'s> {
        MapAt { mtl: &self.m.mtl, material: &self.m.name, keyword: st.keyword, line: st.line }
    }

    /// The statement's options and file; the options it does not use are noted.
    fn parse<'s>(
        &mut self,
        st: &Statement<'s>,
        bump: bool,
    ) -> Result<MapStatement<'s>, SceneError> {
        let mut map = super::mtl_texture::parse_map(st.value)
            .map_err(|p| (self.error)((st.line, format!("{} {p}", st.keyword))))?;
        if let Some(bm) = map.bump_multiplier.filter(|_| !bump) {
            map.unused.push(format!("-bm {bm}"));
        }
        if !map.unused.is_empty() {
            let options = crate::excerpt::excerpt(&map.unused.join(" "));
            let message = format!(
                "{} options '{options}' are not supported; the image is used as it is",
                st.keyword
            );
            self.note(st.line, message);
        }
        Ok(map)
    }

    fn apply(&mut self, lobe: Lobe, material: &mut MaterialDesc) -> Result<(), SceneError> {
        let given = self.given;
        if let Some(st) = &given.map_kd {
            match lobe {
                Lobe::Glass => self.note(st.line, "map_Kd is not used: glass has no diffuse part"),
                Lobe::Metal => self.note(
                    st.line,
                    "map_Kd cannot colour a metal (Pm >= 0.5): its reflectance is Kd",
                ),
                _ => {
                    let map = self.parse(st, false)?;
                    material.texture = Some(colour(&self.at(st), map.file)?);
                }
            }
        }
        if let Some(st) = &given.map_ks {
            self.note(st.line, "map_Ks (a texture of Ks) is not supported");
        }
        if let Some(st) = &given.map_ke {
            let map = self.parse(st, false)?;
            // The image times Ke (times 1 without a Ke, as the image is then the radiance).
            material.emission_texture = Some(colour(&self.at(st), map.file)?);
            material.emission = given.ke.map_or(Vec3::ONE, |ke| ke.value);
        }
        if let Some(st) = &given.map_d {
            let map = self.parse(st, false)?;
            let (texture, _) = data(&self.at(st), map.file, true)?;
            if material.opacity.is_some() {
                self.note(
                    st.line,
                    "d or Tr is not applied with map_d: the map alone is the opacity",
                );
            }
            material.opacity = Some(Opacity::Texture(texture));
        }
        if let Some(st) = &given.norm {
            let map = self.parse(st, true)?;
            self.normal_strength(st, &map);
            material.normal_map = Some(data(&self.at(st), map.file, false)?.0);
        }
        if let Some(st) = &given.bump {
            if given.norm.is_some() {
                let message = format!("{} is not used: norm gives the normal map", st.keyword);
                self.note(st.line, message);
                return Ok(());
            }
            let map = self.parse(st, true)?;
            let (texture, image) = data(&self.at(st), map.file, false)?;
            if looks_like_normal_map(&image) {
                self.note(
                    st.line,
                    format!(
                        "{}'s image looks like a tangent-space normal map (bluish, its mean near \
                         (0.5, 0.5, 1)): it is used as one",
                        st.keyword
                    ),
                );
                self.normal_strength(st, &map);
                material.normal_map = Some(texture);
            } else {
                let factor = map.bump_multiplier.unwrap_or(1.0);
                material.bump_map = Some(BumpMapDesc { texture, factor, scale: BumpScale::Scene });
            }
        }
        Ok(())
    }

    fn normal_strength(&mut self, st: &Statement, map: &MapStatement) {
        if map.bump_multiplier.is_some_and(|bm| bm != 1.0) {
            self.note(st.line, "a normal map's strength (-bm other than 1) is not supported");
        }
    }
}

//! The scene the 3D exporters ([`crate::glb`], [`crate::fbx`]) write, and the preparation they
//! share: storey groups, the Z-up to Y-up conversion, element pivots, cleaned triangles with flat
//! normals, colours and the distinct materials.
//!
//! Layout, identical in both formats:
//!
//! - One group node per storey of [`SceneInput::storeys`], in that order, translated to
//!   `(0, elevation, 0)`; then, only when some element has no storey or one not in the list, a
//!   group named [`NO_STOREY`] at the origin. Storeys without elements still get their node.
//! - Under its group, one node per element of [`SceneInput::elements`], in input order, so the
//!   element nodes are exactly `elements.len()`. An element whose mesh has no usable triangle
//!   (empty, or every triangle degenerate, non-finite or out of range) still gets its node, with
//!   no mesh, at its group's origin.
//! - An element node sits at its pivot, the bottom centre of its bounding box (centre in plan,
//!   lowest point in height), and its vertices are relative to it: the pivot is a natural
//!   handle in Unity and keeps single-precision vertices exact to well under a millimetre even
//!   in georeferenced models far from the origin.
//! - Coordinates are metres in a right-handed Y-up frame: IFC's `(x, y, z)` (Z up) becomes
//!   `(x, z, -y)`, a rotation, so triangle winding (counter-clockwise from outside) is kept.

use std::collections::HashMap;

use glam::DVec3;
use poinav_geom::ElementMesh;
use poinav_ifc::spatial::Storey;
use poinav_ifc::EntityId;
use poinav_poi::{Classification, Classified};
use rustc_hash::FxHashMap;

use crate::palette;

/// The name of the group holding elements without a (listed) storey.
pub const NO_STOREY: &str = "No storey";

/// What a 3D export contains.
#[derive(Debug, Clone, Copy)]
pub struct SceneInput<'a> {
    /// The model's storeys, in the order their nodes get (`spatial_structure(..).storeys`:
    /// by elevation).
    pub storeys: &'a [Storey],
    /// One mesh per element, world metres, Z up (`poinav_geom::mesh_model(..).elements`).
    pub elements: &'a [ElementMesh],
    /// The POI classification, when the model was enriched; its category, type, roles and
    /// accessibility status go into each classified element's metadata.
    pub poi: Option<&'a Classification>,
}

/// IFC's Z-up frame to the Y-up frame of glTF and FBX: `(x, y, z)` -> `(x, z, -y)`.
pub fn z_up_to_y_up(p: DVec3) -> DVec3 {
    DVec3::new(p.x, p.z, -p.y)
}

/// A group node: one storey, or the [`NO_STOREY`] group.
#[derive(Debug)]
pub(crate) struct Group<'a> {
    /// The storey, `None` for the [`NO_STOREY`] group.
    pub storey: Option<&'a Storey>,
    /// Display name: the storey's name, else its GlobalId, else `Storey #id`.
    pub label: String,
    /// Translation (Y up, metres): `(0, elevation, 0)`.
    pub origin: DVec3,
    /// Indices into [`Prepared::elements`], in input order.
    pub elements: Vec<usize>,
}

/// One element ready to be written.
#[derive(Debug)]
pub(crate) struct Element<'a> {
    /// The input.
    pub source: &'a ElementMesh,
    /// Display name: the element's Name, else its class.
    pub label: String,
    /// Its storey's name, when it has a listed storey with a name.
    pub storey_name: Option<&'a str>,
    /// Its classification, when there is one.
    pub poi: Option<&'a Classified>,
    /// Translation relative to its group (Y up, metres).
    pub translation: DVec3,
    /// Vertices relative to the pivot (Y up), only those a triangle uses.
    pub positions: Vec<[f32; 3]>,
    /// Triangles into `positions`, counter-clockwise from outside, none degenerate.
    pub triangles: Vec<[u32; 3]>,
    /// One unit normal per triangle.
    pub normals: Vec<[f32; 3]>,
    /// Index into [`Prepared::materials`]; meaningless (`usize::MAX`) without triangles.
    pub material: usize,
}

impl Element<'_> {
    /// The name written in FBX: the label with the GlobalId in brackets.
    pub fn label_with_guid(&self) -> String {
        if self.source.global_id.is_empty() {
            self.label.clone()
        } else {
            format!("{} [{}]", self.label, self.source.global_id)
        }
    }

    /// POI metadata as (key, value) pairs, roles joined with `;`: `POI_Category`, `POI_Type`,
    /// `POI_PrimaryRoles`, `POI_ConditionalRoles` and, when assessed, `AccessibilityStatus`.
    pub fn poi_pairs(&self) -> Vec<(&'static str, String)> {
        let Some(c) = self.poi else {
            return Vec::new();
        };
        let roles = |r: &[poinav_poi::Role]| r.iter().map(|r| r.label()).collect::<Vec<_>>();
        let mut out = vec![
            ("POI_Category", c.category.label().to_string()),
            ("POI_Type", c.poi_type.label().to_string()),
            ("POI_PrimaryRoles", roles(&c.primary).join(";")),
            ("POI_ConditionalRoles", roles(&c.conditional).join(";")),
        ];
        if let Some(a) = &c.accessibility {
            out.push(("AccessibilityStatus", a.status.label().to_string()));
        }
        out
    }
}

/// A material: one per distinct colour.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Material {
    /// sRGB RGBA.
    pub rgba: [f32; 4],
    /// `#RRGGBB[AA]`.
    pub name: String,
}

/// The whole scene, prepared.
#[derive(Debug)]
pub(crate) struct Prepared<'a> {
    /// Group nodes in output order.
    pub groups: Vec<Group<'a>>,
    /// Elements in input order.
    pub elements: Vec<Element<'a>>,
    /// Distinct colours in order of first use (by an element with triangles).
    pub materials: Vec<Material>,
}

/// Local geometry of one mesh: (translation in world Y-up, positions, triangles, normals).
type Local = (DVec3, Vec<[f32; 3]>, Vec<[u32; 3]>, Vec<[f32; 3]>);

/// Converts, cleans and localises one mesh (see the module docs).
fn localise(mesh: &poinav_geom::Mesh) -> Local {
    let world: Vec<DVec3> = mesh.positions.iter().map(|p| z_up_to_y_up(*p)).collect();
    // Triangles whose indices are in range, whose corners are finite and whose normal exists.
    let usable: Vec<([u32; 3], DVec3)> = mesh
        .triangles
        .iter()
        .filter_map(|t| {
            let [a, b, c] = t.map(|i| world.get(i as usize).copied());
            let (a, b, c) = (a?, b?, c?);
            if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                return None;
            }
            let cross = (b - a).cross(c - a);
            (cross.length() > 1e-10).then(|| (*t, cross.normalize()))
        })
        .collect();
    if usable.is_empty() {
        return (DVec3::ZERO, Vec::new(), Vec::new(), Vec::new());
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for (t, _) in &usable {
        for &i in t {
            lo = lo.min(world[i as usize]);
            hi = hi.max(world[i as usize]);
        }
    }
    let pivot = DVec3::new((lo.x + hi.x) / 2.0, lo.y, (lo.z + hi.z) / 2.0);
    let mut index: FxHashMap<[u32; 3], u32> = FxHashMap::default();
    index.reserve(usable.len());
    let mut positions = Vec::new();
    let mut triangles = Vec::with_capacity(usable.len());
    let mut normals = Vec::with_capacity(usable.len());
    for (t, n) in usable {
        let tri = t.map(|i| {
            let p = (world[i as usize] - pivot).as_vec3().to_array();
            *index.entry(p.map(f32::to_bits)).or_insert_with(|| {
                positions.push(p);
                (positions.len() - 1) as u32
            })
        });
        // Corners that single precision merges make a degenerate triangle: dropped.
        if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
            triangles.push(tri);
            // `+ 0.0` turns -0.0 into 0.0: coplanar triangles then share vertices exactly.
            normals.push(n.as_vec3().normalize().to_array().map(|c| c + 0.0));
        }
    }
    // Vertices only a dropped triangle used stay: harmless, still inside the bounds.
    (pivot, positions, triangles, normals)
}

/// Prepares `scene` for writing.
pub(crate) fn prepare<'a>(scene: &SceneInput<'a>) -> Prepared<'a> {
    prepare_with(scene, |_| {})
}

/// Like [`prepare`], handing each element to `each` as soon as it is ready, before the next
/// one is localised: a writer may take the element's geometry there (its `material` still
/// tells whether it had triangles), so the whole scene's geometry is never held twice.
pub(crate) fn prepare_with<'a>(
    scene: &SceneInput<'a>,
    mut each: impl FnMut(&mut Element<'a>),
) -> Prepared<'a> {
    let mut groups: Vec<Group<'a>> = Vec::new();
    let mut by_storey: HashMap<EntityId, usize> = HashMap::new();
    for s in scene.storeys {
        if by_storey.contains_key(&s.id) {
            continue;
        }
        by_storey.insert(s.id, groups.len());
        let elevation = s.elevation_m.filter(|e| e.is_finite()).unwrap_or(0.0);
        groups.push(Group {
            storey: Some(s),
            label: s.label(),
            origin: DVec3::new(0.0, elevation, 0.0),
            elements: Vec::new(),
        });
    }
    let mut loose: Vec<usize> = Vec::new();
    let mut materials: Vec<Material> = Vec::new();
    let mut material_of: HashMap<[u32; 4], usize> = HashMap::new();
    let mut elements = Vec::with_capacity(scene.elements.len());
    for (i, e) in scene.elements.iter().enumerate() {
        let group = e.storey.and_then(|s| by_storey.get(&s).copied());
        let origin = group.map_or(DVec3::ZERO, |g| groups[g].origin);
        match group {
            Some(g) => groups[g].elements.push(i),
            None => loose.push(i),
        }
        let (pivot, positions, triangles, normals) = localise(&e.mesh);
        let translation = if triangles.is_empty() {
            DVec3::ZERO
        } else {
            pivot - origin
        };
        let rgba = palette::element_color(e.color, &e.class);
        let material = if triangles.is_empty() {
            usize::MAX
        } else {
            *material_of
                .entry(rgba.map(f32::to_bits))
                .or_insert_with(|| {
                    materials.push(Material {
                        rgba,
                        name: palette::hex_name(rgba),
                    });
                    materials.len() - 1
                })
        };
        let label = match &e.name {
            Some(n) if !n.trim().is_empty() => n.clone(),
            _ => e.class.clone(),
        };
        let mut element = Element {
            source: e,
            label,
            storey_name: group.and_then(|g| groups[g].storey?.name.as_deref()),
            poi: scene.poi.and_then(|c| c.get(e.product)),
            translation,
            positions,
            triangles,
            normals,
            material,
        };
        each(&mut element);
        elements.push(element);
    }
    if !loose.is_empty() {
        groups.push(Group {
            storey: None,
            label: NO_STOREY.to_string(),
            origin: DVec3::ZERO,
            elements: loose,
        });
    }
    Prepared {
        groups,
        elements,
        materials,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_geom::Mesh;

    fn element(id: u64, storey: Option<u64>, mesh: Mesh) -> ElementMesh {
        ElementMesh {
            product: EntityId(id),
            global_id: format!("guid{id}"),
            class: "IfcWall".into(),
            name: None,
            storey: storey.map(EntityId),
            mesh,
            color: None,
        }
    }

    fn storey(id: u64, elevation: f64) -> Storey {
        Storey {
            id: EntityId(id),
            global_id: None,
            name: Some(format!("Level {id}")),
            elevation_m: Some(elevation),
        }
    }

    #[test]
    fn converts_to_y_up_and_localises_at_the_bottom_centre() {
        assert_eq!(
            z_up_to_y_up(DVec3::new(1.0, 2.0, 3.0)),
            DVec3::new(1.0, 3.0, -2.0)
        );
        let mesh = Mesh {
            positions: vec![
                DVec3::new(10.0, 20.0, 3.0),
                DVec3::new(12.0, 20.0, 3.0),
                DVec3::new(12.0, 24.0, 3.0),
                DVec3::new(f64::NAN, 0.0, 0.0),
            ],
            // A good triangle, a degenerate one, one with a NaN corner, one out of range.
            triangles: vec![[0, 1, 2], [0, 1, 1], [0, 1, 3], [0, 1, 9]],
        };
        let storeys = [storey(5, 3.0)];
        let elements = [element(1, Some(5), mesh)];
        let p = prepare(&SceneInput {
            storeys: &storeys,
            elements: &elements,
            poi: None,
        });
        let e = &p.elements[0];
        assert_eq!(e.triangles.len(), 1);
        assert_eq!(e.positions.len(), 3);
        // Pivot (11, 3, -22) in Y-up world, storey origin (0, 3, 0).
        assert_eq!(e.translation, DVec3::new(11.0, 0.0, -22.0));
        assert_eq!(e.positions[0], [-1.0, 0.0, 2.0]);
        // Counter-clockwise seen from +Z in IFC: the normal points up (+Y).
        assert_eq!(e.normals[0], [0.0, 1.0, 0.0]);
        assert_eq!(p.groups.len(), 1);
        assert_eq!(p.groups[0].origin, DVec3::new(0.0, 3.0, 0.0));
    }

    #[test]
    fn groups_follow_the_storey_list_and_loose_elements_go_last() {
        let storeys = [storey(5, 0.0), storey(6, 3.0), storey(5, 0.0)];
        let elements = [
            element(1, Some(6), Mesh::default()),
            element(2, None, Mesh::default()),
            element(3, Some(99), Mesh::default()),
            element(4, Some(5), Mesh::default()),
        ];
        let p = prepare(&SceneInput {
            storeys: &storeys,
            elements: &elements,
            poi: None,
        });
        let groups: Vec<(&str, &[usize])> = p
            .groups
            .iter()
            .map(|g| (g.label.as_str(), g.elements.as_slice()))
            .collect();
        assert_eq!(
            groups,
            vec![
                ("Level 5", &[3][..]),
                ("Level 6", &[0][..]),
                (NO_STOREY, &[1, 2][..])
            ]
        );
        assert!(p.materials.is_empty());
        assert_eq!(p.elements[0].label_with_guid(), "IfcWall [guid1]");
    }
}

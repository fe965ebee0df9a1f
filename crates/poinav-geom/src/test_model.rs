//! Test-only: a model from a few STEP instances, for the unit tests of this crate.

use poinav_ifc::Model;

/// The IFC4 model whose DATA section is `data`.
pub(crate) fn ifc4(data: &str) -> Model {
    with_schema("IFC4", data)
}

/// The model of `schema` whose DATA section is `data`.
pub(crate) fn with_schema(schema: &str, data: &str) -> Model {
    let text = format!(
        "ISO-10303-21;HEADER;FILE_SCHEMA(('{schema}'));ENDSEC;DATA;\n{data}\nENDSEC;END-ISO-10303-21;"
    );
    Model::from_bytes("t.ifc", text.into_bytes()).unwrap()
}

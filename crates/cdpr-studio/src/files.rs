//! # Robot files opened in the page
//!
//! The page has no file system: it hands over each file's name and text (picked, dropped or
//! fetched). The format is told by the name, as `cdpr-io` does for paths: `.toml` (cdpr),
//! `NAME_cables.xml` + `NAME_bodies.xml` (CASPR), `.wcrfx` (WireCenter).

use crate::StudioError;
use cdpr_io::{RobotDescription, RobotFormat};
use serde::Deserialize;

/// One file the page read: its name (for the format and for error messages) and its text.
#[derive(Debug, Clone, Deserialize)]
pub struct RobotFileText {
    /// File name, e.g. `ipanema_cables.xml`.
    pub name: String,
    /// The file's text.
    pub text: String,
}

/// The robot of `files`: one TOML or `.wcrfx` file, or a CASPR pair (in any order).
pub(crate) fn parse(files: &[RobotFileText]) -> Result<RobotDescription, StudioError> {
    let first = files
        .first()
        .ok_or_else(|| StudioError::Files("no robot file given".into()))?;
    match RobotFormat::from_path(&first.name)? {
        RobotFormat::Toml => Ok(RobotDescription::parse(&first.text, &first.name)?),
        RobotFormat::WireCenter => Ok(RobotDescription::parse_wcrfx(&first.text, &first.name)?),
        RobotFormat::Caspr => {
            let find = |suffix: &str| {
                files
                    .iter()
                    .find(|f| f.name.to_ascii_lowercase().ends_with(suffix))
            };
            let cables = find("_cables.xml").ok_or_else(|| {
                StudioError::Files(format!(
                    "{}: a CASPR model is two files: open NAME_cables.xml and NAME_bodies.xml together",
                    first.name
                ))
            })?;
            let bodies = find("_bodies.xml").ok_or_else(|| {
                StudioError::Files(format!(
                    "{}: the CASPR bodies file NAME_bodies.xml is missing: open both files together",
                    cables.name
                ))
            })?;
            Ok(RobotDescription::parse_caspr(
                &cables.text,
                &cables.name,
                &bodies.text,
                &bodies.name,
                None,
            )?)
        }
        _ => Err(StudioError::Files(format!(
            "{}: unknown robot file type",
            first.name
        ))),
    }
}

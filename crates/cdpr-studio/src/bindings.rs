//! # The JavaScript bindings
//!
//! The page's interface (wasm-bindgen): JSON strings in, JSON strings out, errors as the
//! message of a thrown `Error`. Compiled for `wasm32` only.

use crate::{PathSettings, RobotFileText, RobotTable, SectionSettings, Studio, StudioError};
use wasm_bindgen::prelude::*;

fn js(e: StudioError) -> JsError {
    JsError::new(&e.to_string())
}

fn json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string(v).expect("the studio's reports serialise")
}

fn numbers(text: &str, what: &str) -> Result<Option<Vec<f64>>, JsError> {
    if text.trim().is_empty() {
        return Ok(None);
    }
    text.split(',')
        .map(|p| {
            p.trim()
                .parse::<f64>()
                .map_err(|_| JsError::new(&format!("{what}: `{}` is not a number", p.trim())))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// A studio session for the page.
#[wasm_bindgen]
pub struct StudioSession(Studio, Vec<u8>);

#[wasm_bindgen]
impl StudioSession {
    /// Opens a robot from `[{"name": …, "text": …}, …]` (one file, or a CASPR pair).
    #[wasm_bindgen(constructor)]
    pub fn new(files_json: &str) -> Result<StudioSession, JsError> {
        let files: Vec<RobotFileText> =
            serde_json::from_str(files_json).map_err(|e| js(e.into()))?;
        Studio::open(&files)
            .map(|s| StudioSession(s, Vec::new()))
            .map_err(js)
    }

    /// The robot table (JSON).
    pub fn table(&self) -> String {
        json(&self.0.table())
    }

    /// Applies an edited robot table (JSON).
    pub fn edit(&mut self, table_json: &str) -> Result<(), JsError> {
        let t: RobotTable = serde_json::from_str(table_json).map_err(|e| js(e.into()))?;
        self.0.edit(&t).map_err(js)
    }

    /// The state at a pose (JSON): `pose` and `wrench` are comma-separated numbers (wrench may
    /// be empty).
    pub fn state(&self, pose: &str, method: &str, wrench: &str) -> Result<String, JsError> {
        let q = numbers(pose, "pose")?.unwrap_or_default();
        let w = numbers(wrench, "wrench")?;
        self.0
            .state(&q, method, w.as_deref())
            .map(|s| json(&s))
            .map_err(js)
    }

    /// The 3-D scene at a pose (JSON).
    pub fn scene(&self, pose: &str) -> Result<String, JsError> {
        let q = numbers(pose, "pose")?.unwrap_or_default();
        self.0.scene(&q).map(|s| json(&s)).map_err(js)
    }

    /// The workspace boundary mesh (JSON); its STL file is then [`Self::mesh_stl`].
    pub fn workspace_mesh(
        &mut self,
        pose: &str,
        grid: usize,
        method: &str,
        wrench: &str,
    ) -> Result<String, JsError> {
        let q = numbers(pose, "pose")?.unwrap_or_default();
        let w = numbers(wrench, "wrench")?;
        let m = self
            .0
            .workspace_mesh(&q, grid, method, w.as_deref())
            .map_err(js)?;
        let text = json(&m);
        self.1 = m.stl;
        Ok(text)
    }

    /// The workspace on a grid (JSON: `cdpr workspace --grid M --json`'s report and the
    /// feasible points).
    pub fn workspace_grid(
        &self,
        pose: &str,
        grid: usize,
        method: &str,
        wrench: &str,
    ) -> Result<String, JsError> {
        let q = numbers(pose, "pose")?.unwrap_or_default();
        let w = numbers(wrench, "wrench")?;
        self.0
            .workspace_grid(&q, grid, method, w.as_deref())
            .map(|g| json(&g))
            .map_err(js)
    }

    /// The plane section `axis = value` (m) of the workspace by the chord method (JSON), seeded
    /// by a `grid`, chord length `chord` (m).
    #[allow(clippy::too_many_arguments)]
    pub fn workspace_section(
        &self,
        pose: &str,
        axis: usize,
        value: f64,
        grid: usize,
        chord: f64,
        method: &str,
        wrench: &str,
    ) -> Result<String, JsError> {
        let q = numbers(pose, "pose")?.unwrap_or_default();
        let w = numbers(wrench, "wrench")?;
        let s = SectionSettings {
            axis,
            value,
            grid,
            chord,
        };
        self.0
            .workspace_section(&q, s, method, w.as_deref())
            .map(|r| json(&r))
            .map_err(js)
    }

    /// A path or timed trajectory (JSON settings: `from`, `to`, `samples`, `method`, `wrench`,
    /// `time_law`, `duration`, `dt`, `dynamics`); the JSON of `cdpr trajectory --json`.
    pub fn trajectory(&self, settings_json: &str) -> Result<String, JsError> {
        let s: PathSettings = serde_json::from_str(settings_json).map_err(|e| js(e.into()))?;
        self.0.trajectory(&s).map(|r| json(&r)).map_err(js)
    }

    /// The binary STL file of the last workspace mesh (empty before the first).
    pub fn mesh_stl(&self) -> Vec<u8> {
        self.1.clone()
    }

    /// The robot as a cdpr TOML file.
    pub fn to_toml(&self) -> String {
        self.0.to_toml()
    }

    /// The robot as a WireCenter `.wcrfx` file.
    pub fn to_wcrfx(&self) -> Result<String, JsError> {
        self.0.to_wcrfx().map_err(js)
    }
}

//! Several figures side by side in one image (thesis Figs. 6.4, 6.5, 6.8, 6.9 are 3 × 3 grids
//! of workspaces; Figs. 6.10–6.15 pair a starting and an optimised design).

use super::{DrawResult, Figure};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Panels laid out row by row in `columns` columns under a common title.
#[derive(Debug, Clone, Default)]
pub struct Panels<F> {
    /// Title above all panels.
    pub title: String,
    /// Note lines under the title (e.g. the volume and the criteria).
    pub notes: Vec<String>,
    /// Number of columns (≥ 1); rows follow from the number of panels.
    pub columns: usize,
    /// Size of one panel in pixels.
    pub panel_size: (u32, u32),
    /// The panels, row by row.
    pub panels: Vec<F>,
}

const TITLE_HEIGHT: u32 = 44;
const NOTE_HEIGHT: u32 = 20;

impl<F> Panels<F> {
    fn header_height(&self) -> u32 {
        TITLE_HEIGHT + NOTE_HEIGHT * self.notes.len() as u32
    }

    fn grid(&self) -> (usize, usize) {
        let columns = self.columns.max(1);
        (self.panels.len().div_ceil(columns).max(1), columns)
    }
}

impl<F: Figure> Figure for Panels<F> {
    fn size(&self) -> (u32, u32) {
        let (rows, columns) = self.grid();
        (
            self.panel_size.0 * columns as u32,
            self.panel_size.1 * rows as u32 + self.header_height(),
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (title, body) = root.split_vertically(self.header_height());
        title.draw(&Text::new(
            self.title.clone(),
            (12, 10),
            ("sans-serif", 22).into_font(),
        ))?;
        for (k, note) in self.notes.iter().enumerate() {
            title.draw(&Text::new(
                note.clone(),
                (14, TITLE_HEIGHT as i32 - 4 + NOTE_HEIGHT as i32 * k as i32),
                ("sans-serif", 15).into_font(),
            ))?;
        }
        let cells = body.split_evenly(self.grid());
        for (panel, cell) in self.panels.iter().zip(&cells) {
            panel.draw(cell)?;
        }
        Ok(())
    }
}

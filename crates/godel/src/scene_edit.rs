//! One home for "this scene with some fields replaced": the scene's own text as a TOML
//! table, edited (an observer moved, a camera replaced, the tracing method set), then read
//! again with the usual checks (`scene::Scene::from_str`). Fly-through frames (`flight`),
//! explore's frames (`cmd::explore`) and explore's exact renders and recorded flights (`keep`)
//! all make their scenes here, so that each is exactly the scene a user would write with those
//! fields: its data file embeds that text.

use scene::{Scene, SceneError};
use toml::{Table, Value};

/// Why an edited scene could not be made.
#[derive(Debug)]
pub enum EditError {
    /// The scene's own text could not be read as a table again, or the edited table written.
    Text(String),
    /// The edited scene is refused by the usual checks (the field named).
    Scene(SceneError),
}

impl std::fmt::Display for EditError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EditError::Text(why) => write!(f, "{why}"),
            EditError::Scene(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for EditError {}

/// The scene text `text` (read from `file`: messages and relative image paths) after `edit`,
/// read again with the usual checks.
pub fn edited(text: &str, file: &str, edit: impl FnOnce(&mut Table)) -> Result<Scene, EditError> {
    edited_table(table_of(text, file)?, file, edit)
}

/// The scene text `text` (read from `file`) as a table, to edit many times over
/// ([`edited_table`]) having read it once.
pub fn table_of(text: &str, file: &str) -> Result<Table, EditError> {
    text.parse()
        .map_err(|e| EditError::Text(format!("{file}: cannot re-read the scene: {e}")))
}

/// [`edited`] of a scene already read as a table ([`table_of`]).
pub fn edited_table(
    mut table: Table,
    file: &str,
    edit: impl FnOnce(&mut Table),
) -> Result<Scene, EditError> {
    edit(&mut table);
    let text = toml::to_string(&table).map_err(|e| EditError::Text(format!("{file}: {e}")))?;
    Scene::from_str(&text, file).map_err(EditError::Scene)
}

/// The table at `key` of `table`, made a table when missing (or not a table).
pub fn section<'a>(table: &'a mut Table, key: &str) -> &'a mut Table {
    let entry = table
        .entry(key)
        .or_insert_with(|| Value::Table(Table::new()));
    if !entry.is_table() {
        *entry = Value::Table(Table::new());
    }
    match entry {
        Value::Table(t) => t,
        _ => unreachable!("made a table just above"),
    }
}

"""docs/python.ipynb runs end to end (a fresh kernel of this Python executes every cell) and
draws its figures; the copy in the repository is an executed one, with its figures."""

from __future__ import annotations

import nbformat
from nbclient import NotebookClient

from conftest import REPO

NOTEBOOK = REPO / "docs" / "python.ipynb"


def figures(notebook) -> int:
    return sum(
        "image/png" in output.get("data", {})
        for cell in notebook.cells
        if cell.cell_type == "code"
        for output in cell.get("outputs", [])
    )


def test_the_notebook_runs_end_to_end(tmp_path):
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    code = [c for c in notebook.cells if c.cell_type == "code"]
    assert len(code) >= 4
    # Executed from a scratch folder: whatever it writes stays out of the repository.
    client = NotebookClient(notebook, timeout=600, kernel_name="python3", coalesce_streams=True,
                            resources={"metadata": {"path": str(tmp_path)}})
    client.execute()  # raises CellExecutionError on the first failing cell
    for cell in code:
        assert cell.execution_count is not None
        assert not any(o.output_type == "error" for o in cell.outputs)
    # The picture with g and t_emit, and the light ray: two figures.
    assert figures(notebook) >= 2


def test_the_committed_notebook_is_executed():
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    code = [c for c in notebook.cells if c.cell_type == "code"]
    assert all(c.execution_count is not None for c in code)
    assert figures(notebook) >= 2

"""The example notebook runs from top to bottom."""

import nbformat
import pytest
from nbclient import NotebookClient


@pytest.mark.slow
def test_the_example_notebook_runs(root):
    path = root / "examples" / "python_quickstart.ipynb"
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(
        notebook, timeout=600, kernel_name="python3", resources={"metadata": {"path": path.parent}}
    )
    client.execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    printed = "".join(o.get("text", "") for o in outputs if o.get("output_type") == "stream")
    assert "transitions: 7483" in printed
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) >= 2
    shown = [o for o in outputs if "text/markdown" in o.get("data", {})]
    assert shown and "der(" in shown[0]["data"]["text/markdown"]

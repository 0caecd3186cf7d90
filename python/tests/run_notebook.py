"""Runs one notebook of examples/notebooks headless, as CTest's notebook_<name> tests do.

    python3 run_notebook.py NOTEBOOK.ipynb

Checks that the stored notebook carries no outputs (it is kept clean in git), executes every
cell in a fresh kernel of this python3 (nbclient; the kernel inherits PYTHONPATH), fails on
the first cell that raises, and requires each plotting notebook to draw its figures (PNG
outputs). Exit 0 on success, 1 on failure, 2 on bad usage. The notebook file is not changed.
"""
import os
import sys
import time

from notebook_runner import kernel_for_this_python


def stored_outputs(nb):
    """Cells that carry outputs or execution counts in the stored file."""
    return [i for i, cell in enumerate(nb.cells)
            if cell.cell_type == "code" and (cell.get("outputs") or cell.get("execution_count") is not None)]


def main(argv):
    if len(argv) != 2 or not argv[1].endswith(".ipynb"):
        print("usage: run_notebook.py NOTEBOOK.ipynb", file=sys.stderr)
        return 2
    import nbclient
    import nbformat
    path = os.path.abspath(argv[1])
    nb = nbformat.read(path, as_version=4)
    nbformat.validate(nb)
    dirty = stored_outputs(nb)
    if dirty:
        print("FAIL %s: stored with outputs in code cells %s (clear them before committing)" % (path, dirty))
        return 1
    start = time.perf_counter()
    with kernel_for_this_python() as kernel_name:
        client = nbclient.NotebookClient(nb, timeout=60, kernel_name=kernel_name,
                                         resources={"metadata": {"path": os.path.dirname(path)}})
        try:
            client.execute()
        except nbclient.exceptions.CellExecutionError as error:
            print("FAIL %s: a cell raised\n%s" % (path, error))
            return 1
    elapsed = time.perf_counter() - start
    figures = sum(1 for cell in nb.cells for out in cell.get("outputs", [])
                  if "image/png" in out.get("data", {}))
    plots = sum(1 for cell in nb.cells if cell.cell_type == "code" and "plt.show()" in cell.source)
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            if out.get("output_type") == "stream":
                sys.stdout.write(out.get("text", ""))
    print("%s: %d cells run in %.1f s, %d figures" % (os.path.basename(path), len(nb.cells), elapsed, figures))
    if figures < plots:
        print("FAIL %s: %d cells call plt.show() but %d figures were drawn" % (path, plots, figures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

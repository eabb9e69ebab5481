# notebooks/quickstart.ipynb is committed without outputs and executes (Debian's nbconvert) on a quick-start run folder.
source "$(dirname "$0")/common.sh"
nb="$SOURCE_DIR/notebooks/quickstart.ipynb"
/usr/bin/python3 - "$nb" <<'PY'
import nbformat, sys
nb = nbformat.read(sys.argv[1], as_version=4)
dirty = [i for i, c in enumerate(nb.cells) if c.cell_type == "code" and (c.outputs or c.execution_count)]
assert not dirty, f"{sys.argv[1]}: cells {dirty} carry outputs; strip them (jupyter nbconvert --clear-output --inplace)"
print("ok: committed notebook has no outputs")
PY
cd "$SOURCE_DIR"
"$BLOCKLAB" run configs/quickstart.yaml --out "$WORK/run" --quiet >/dev/null
cp "$nb" "$WORK/nb.ipynb"
BLOCKLAB_RUN_DIR="$WORK/run" /usr/bin/jupyter nbconvert --to notebook --execute \
  --ExecutePreprocessor.timeout=300 --output "$WORK/executed.ipynb" "$WORK/nb.ipynb"
[ -s "$WORK/executed.ipynb" ] || die "notebook did not execute"
ls "$WORK/run"/*.png >/dev/null 2>&1 || die "notebook wrote no figure into the run folder"
# Every cell that draws a figure shows it inline: an image/png output in the executed notebook.
/usr/bin/python3 - "$WORK/executed.ipynb" <<'PY' || die "a plot cell has no inline image"
import nbformat, sys
nb = nbformat.read(sys.argv[1], as_version=4)
plot_cells = [i for i, c in enumerate(nb.cells) if c.cell_type == "code" and "plt.subplots" in c.source]
assert plot_cells, "no plot cell found"
missing = [i for i in plot_cells if not any("image/png" in o.get("data", {}) for o in nb.cells[i].outputs)]
assert not missing, f"cells {missing} draw a figure but show no inline image"
print(f"ok: {len(plot_cells)} plot cell(s), each with an inline image")
PY
echo "ok: notebook executed and wrote $(ls "$WORK/run"/*.png | wc -l) figure(s)"

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
BLOCKLAB_RUN_DIR="$WORK/run" MPLBACKEND=Agg /usr/bin/jupyter nbconvert --to notebook --execute \
  --ExecutePreprocessor.timeout=300 --output "$WORK/executed.ipynb" "$WORK/nb.ipynb"
[ -s "$WORK/executed.ipynb" ] || die "notebook did not execute"
ls "$WORK/run"/*.png >/dev/null 2>&1 || die "notebook wrote no figure into the run folder"
echo "ok: notebook executed and wrote $(ls "$WORK/run"/*.png | wc -l) figure(s)"

"""One table across a batch's sequences and methods, from each sequence's bmfr eval scores:
results.csv, results.json and index.html (which links each sequence's report)."""
import csv
import html
import io
import json
import os

from .tasks import read_json, write_text_atomically


def _write_text_atomically(path, text):
    """Replaces `path` with `text` unless it holds that already (a resumed batch with nothing
    to do rewrites nothing)."""
    try:
        with open(path, encoding="utf-8", newline="") as f:
            if f.read() == text:
                return
    except OSError:
        pass
    write_text_atomically(path, text)


def gather(plan, out):
    """Writes the three tables; returns the rows (one per sequence and method, noisy first)."""
    rows = []
    for seq in plan.sequences:
        table = read_json(os.path.join(out, "scores", seq.name, "table.json"))
        if not isinstance(table, dict):
            continue
        for name in ["noisy"] + [m.name for m in plan.methods]:
            scores = table.get("methods", {}).get(name)
            if not isinstance(scores, dict):
                continue
            row = {"sequence": seq.name, "method": name, "frames": seq.frames,
                   "size": f"{seq.width}x{seq.height}",
                   "reference_spp": seq.reference_samples}
            for metric in plan.metrics:
                row[metric] = scores.get("mean", {}).get(metric)
            row["ms_per_frame"] = scores.get("ms_per_frame")
            row["machine"] = scores.get("machine", "")
            rows.append(row)
    columns = ["sequence", "method", "frames", "size", "reference_spp"] + plan.metrics + [
        "ms_per_frame", "machine"]
    text = io.StringIO()
    writer = csv.DictWriter(text, columns, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: ("" if v is None else f"{v:.6g}" if isinstance(v, float) else v)
                         for k, v in row.items()})
    _write_text_atomically(os.path.join(out, "results.csv"), text.getvalue())
    document = {"metrics": plan.metrics, "rows": rows,
                "color_space": "as bmfr eval: tone-mapped clamp(x^(1/2.2), 0, 1) but relMSE "
                               "(linear)"}
    _write_text_atomically(os.path.join(out, "results.json"),
                           json.dumps(document, indent=1, sort_keys=True) + "\n")
    _write_text_atomically(os.path.join(out, "index.html"), _html(plan, rows, columns))
    return rows


def _html(plan, rows, columns):
    head = "".join(f"<th>{html.escape(c)}</th>" for c in columns)
    body = []
    for row in rows:
        cells = []
        for c in columns:
            v = row.get(c)
            text = "" if v is None else f"{v:.4g}" if isinstance(v, float) else str(v)
            if c == "sequence":
                text = (f'<a href="scores/{html.escape(str(v))}/report.html">'
                        f"{html.escape(str(v))}</a>")
            else:
                text = html.escape(text)
            cells.append(f"<td>{text}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return ("<!doctype html><meta charset=utf-8><title>bmfr batch</title>"
            "<style>body{font-family:sans-serif}td,th{padding:2px 8px;text-align:right}"
            "td:nth-child(-n+2){text-align:left}</style>"
            f"<h1>bmfr batch: {len(plan.sequences)} sequences, {len(plan.methods)} methods</h1>"
            "<p>Means over each sequence's frames, scored by <code>bmfr eval</code> against the "
            "sequence's reference (tone-mapped clamp(x^(1/2.2), 0, 1); relMSE linear); "
            "ms/frame is the denoise time on the machine named. Each sequence links its "
            "report.</p>"
            f"<table><tr>{head}</tr>{''.join(body)}</table>\n")

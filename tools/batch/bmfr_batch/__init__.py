"""bmfr batch: render, denoise and score many sequences on a Ray cluster (docs/batch.md)."""

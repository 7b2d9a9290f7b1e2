"""Denoises a sequence folder with bmfr's Python module and writes the frames as EXR, with the
same bits as `bmfr denoise SEQ -o OUT --no-png`. Usage: denoise_sequence.py SEQ OUT [FILTER]"""
import os
import sys

import bmfr

seq_dir, out_dir = sys.argv[1], sys.argv[2]
name = sys.argv[3] if len(sys.argv) > 3 else "bmfr"
sequence = bmfr.read_sequence(seq_dir)  # either layout; frames are dicts of numpy arrays
f = bmfr.Filter(name, **sequence.settings)  # the sequence's own limits, as the CLI takes them
os.makedirs(out_dir, exist_ok=True)
for frame in sequence:
    image = f.denoise_frame(frame)  # every buffer the frame holds, motion vectors included
    bmfr.write_exr(os.path.join(out_dir, f"denoised_{frame['index']:04d}.exr"), image)
    print(f"frame {frame['index']}: {f.stats['total_ms']:.1f} ms")

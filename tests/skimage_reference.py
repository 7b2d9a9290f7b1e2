"""Independent SSIM / PSNR reference for tests/metrics_test.cpp (scikit-image)."""
import sys

import numpy as np
from skimage.metrics import peak_signal_noise_ratio, structural_similarity

a_path, b_path, w, h, c = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
a = np.fromfile(a_path, dtype=np.float32).reshape(h, w, c).astype(np.float64)
b = np.fromfile(b_path, dtype=np.float32).reshape(h, w, c).astype(np.float64)
s = structural_similarity(a, b, channel_axis=2, gaussian_weights=True, sigma=1.5,
                          use_sample_covariance=False, data_range=1.0)
p = peak_signal_noise_ratio(a, b, data_range=1.0)
print(f"{s:.9f} {p:.9f}")

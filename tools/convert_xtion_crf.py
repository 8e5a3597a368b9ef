#!/usr/bin/env python3
"""Converts the HDRFusion authors' Xtion calibration (OpenCV FileStorage YAML, MIT licence,
../shared/data/xtion_crf) into a sensor.json profile (docs/formats.md) for resources/sensors/.

Interpretation (the authors' MATLAB calibration code is not public):
  inv_Cam_Response_Func  256x3, row = level, column = channel in R, G, B order as the
                         authors' code indexes it  -> response.inverse.{r,g,b}
  noise_Level_Func       1x6 = (sigma_s, sigma_c) per channel, standard deviations in the
                         units of the inverse response -> noise.sigma_s / noise.sigma_c
  XtionRGB_intrinsics    fx, fy, cx, cy, width, height -> camera
Depth scale 1000 (OpenNI delivers millimetres)."""
import json, re, sys

def matrix(text, name):
    m = re.search(name + r':\s*!!opencv-matrix\s*rows:\s*(\d+)\s*cols:\s*(\d+)\s*dt:\s*\w\s*data:\s*\[(.*?)\]', text, re.S)
    rows, cols = int(m.group(1)), int(m.group(2))
    vals = [float(v) for v in m.group(3).replace('\n', ' ').split(',')]
    assert len(vals) == rows * cols, name
    return [vals[r * cols:(r + 1) * cols] for r in range(rows)]

def scalar(text, name):
    return float(re.search(name + r':\s*([-\d.eE]+)', text).group(1))

crf_path, intr_path, out_path, serial = sys.argv[1:5]
crf = open(crf_path).read()
intr = open(intr_path).read()
inv = matrix(crf, 'inv_Cam_Response_Func')
nlf = matrix(crf, 'noise_Level_Func')[0]
for c in range(3):
    col = [row[c] for row in inv]
    assert all(b >= a for a, b in zip(col, col[1:])), 'non-monotonic channel %d' % c
profile = {
    'camera': {'width': int(scalar(intr, '_sWidth')), 'height': int(scalar(intr, '_sHeight')),
               'fx': scalar(intr, '_fFx'), 'fy': scalar(intr, '_fFy'),
               'cx': scalar(intr, '_u'), 'cy': scalar(intr, '_v')},
    'depth': {'scale': 1000.0},
    'response': {'inverse': {ch: [row[c] for row in inv] for c, ch in enumerate('rgb')}},
    'noise': {'sigma_s': [nlf[0], nlf[2], nlf[4]], 'sigma_c': [nlf[1], nlf[3], nlf[5]]},
    'source': {'name': 'Asus Xtion PRO LIVE colour camera, serial ' + serial,
               'origin': 'github.com/ShudaLi/HDRFusion commit ab7242cd9b1686900c9bdc525f3f300740672ba0, hdr_fusion/data/' + serial + '/crf.yml',
               'licence': 'MIT, Copyright (c) 2016 Shuda Li (see LICENSE-xtion-crf.txt)'},
}
json.dump(profile, open(out_path, 'w'), indent=1)
print('wrote', out_path)

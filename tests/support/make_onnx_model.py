#!/usr/bin/python3
"""Writes a tiny ONNX model whose output is fixed: GlobalAveragePool -> Flatten -> MatMul(zeros) -> Add(constant
detections) -> Reshape. Loads in OpenCV 4.6's DNN module and behaves like a YOLO export with known output.

usage: make_onnx_model.py OUT.onnx IMGSZ LAYOUT ROWS_JSON
  LAYOUT: v5 ([1, N, 5+nc], rows are cx cy w h obj cls...) or v8 ([1, 4+nc, N], rows are cx cy w h cls...)
  ROWS_JSON: e.g. '[[320, 320, 100, 50, 0.9, 0.8, 0.1]]', coordinates in letterboxed input pixels; padded
  with all-zero rows to the anchor count of a real export (25200 for YOLOv5, 8400 for YOLOv8 at 640)
"""
import json
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

out, imgsz, layout, rows = sys.argv[1], int(sys.argv[2]), sys.argv[3], np.array(json.loads(sys.argv[4]), np.float32)
# Pad with empty rows to the anchor count a real export has: YOLOv5 3 anchors x (s/8^2 + s/16^2 + s/32^2),
# YOLOv8 one per grid cell.
cells = (imgsz // 8) ** 2 + (imgsz // 16) ** 2 + (imgsz // 32) ** 2
total = 3 * cells if layout == "v5" else cells
rows = np.vstack([rows, np.zeros((total - rows.shape[0], rows.shape[1]), np.float32)])
n, width = rows.shape
flat = rows.reshape(1, -1) if layout == "v5" else rows.T.copy().reshape(1, -1)
shape = [1, n, width] if layout == "v5" else [1, width, n]
nodes = [
    helper.make_node("GlobalAveragePool", ["images"], ["pooled"]),
    helper.make_node("Flatten", ["pooled"], ["flat"]),
    helper.make_node("MatMul", ["flat", "zeros"], ["nothing"]),
    helper.make_node("Add", ["nothing", "detections"], ["sum"]),
    helper.make_node("Reshape", ["sum", "shape"], ["output0"]),
]
inits = [
    numpy_helper.from_array(np.zeros((3, flat.shape[1]), np.float32), "zeros"),
    numpy_helper.from_array(flat.astype(np.float32), "detections"),
    numpy_helper.from_array(np.array(shape, np.int64), "shape"),
]
graph = helper.make_graph(
    nodes, "fixed_detections",
    [helper.make_tensor_value_info("images", TensorProto.FLOAT, [1, 3, imgsz, imgsz])],
    [helper.make_tensor_value_info("output0", TensorProto.FLOAT, shape)], inits)
model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 12)])
model.ir_version = 7
onnx.checker.check_model(model)
onnx.save(model, out)

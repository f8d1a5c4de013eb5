#!/usr/bin/env python3
"""Writes the seed corpus of the fuzzers (tests/fuzz/corpus/<fuzzer>/): a few valid files and the nasty inputs
that break careless parsers (deep nesting, huge integers, 1e309, a BOM, long tokens, duplicate YAML keys, extra
YAML documents, unknown pairs keys, ...). The files are committed; rerun after adding a case: python3 tests/fuzz/make_corpus.py"""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
BOM = "\ufeff"
DEEP = 66000  # the nesting depth that crashed `ipd table` (exit 139)


def write(fuzzer, name, text):
    d = os.path.join(HERE, "corpus", fuzzer)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(text.encode("utf-8", "surrogatepass") if isinstance(text, str) else text)


def nested(depth, inner="0"):
    return "[" * depth + inner + "]" * depth


# --- YOLO label files -------------------------------------------------------------------------------------
L = "fuzz_labels"
write(L, "valid_gt.txt", "0 0.5 0.5 0.1 0.2\n1 0.25 0.75 0.05 0.05\n0 0.9 0.1 0.02 0.03\n")
write(L, "valid_pred.txt", "0 0.5 0.5 0.1 0.2 0.91\n0 0.26 0.74 0.05 0.06 0.30\n")
write(L, "valid_comments_blank_crlf.txt", "# rocks\r\n\r\n0 0.5 0.5 0.1 0.2\r\n   \r\n0 0.3 0.3 0.1 0.1\r\n")
write(L, "bom.txt", BOM + "0 0.5 0.5 0.1 0.2\n")
write(L, "huge_integers.txt", "99999999999999999999 0.5 0.5 0.1 0.1\n4294967296 0.5 0.5 0.1 0.1\n-1 0.5 0.5 0.1 0.1\n")
write(L, "overflow_1e309.txt", "0 1e309 0.5 0.1 0.1\n0 0.5 -1e309 0.1 0.1\n0 0.5 0.5 1e-400 0.1\n")
write(L, "nan_inf_hex.txt", "0 nan 0.5 0.1 0.1\n0 inf 0.5 0.1 0.1\n0 0x1p-2 0.5 0.1 0.1\n0 0.5 0.5 -0 0.1\n")
write(L, "zero_negative_size.txt", "0 0.5 0.5 0 0.1\n0 0.5 0.5 0.1 -0.1\n0 1.5 0.5 0.1 0.1\n")
write(L, "wrong_columns.txt", "0 0.5 0.5 0.1\n0 0.5 0.5 0.1 0.1 0.9 7\n\t0\t0.5\t0.5\t0.1\t0.1\n")
write(L, "long_token_out_of_range.txt", "0 5" + "0" * 100000 + " 0.5 0.1 0.1\n")
write(L, "long_token_garbage.txt", "x" * 100000 + "\n")
write(L, "long_token_in_range.txt", "0 0." + "0" * 100000 + "5 0.5 0.1 0.1\n")
write(L, "many_bad_lines.txt", "garbage line\n" * 5000)
write(L, "nul_and_cr.txt", b"0 0.5 0.5 0.1 0.1\x00\n0\r0.5 0.5 0.1 0.1\n\x00\x00\x00\n0 0.5\x000.5 0.1 0.1\n")
write(L, "no_final_newline.txt", "0 0.5 0.5 0.1 0.2")
write(L, "invalid_utf8.txt", b"\xff\xfe0 0.5 0.5 0.1 0.1\n\xc3\x28 0.5 0.5 0.1 0.1\n")
write(L, "empty.txt", "")
write(L, "nul_block_in_number.txt", b"0 0.5 0.5 0.1 0.20\x00\x00\x00\x00\n0 0.5 0.5 0.1 0.1 0.9\x00 4782\n")
write(L, "bytes_after_number.txt", "0 0.5 0.5e 0.1 0.1\n0 0.5\x01 0.5 0.1 0.1\n0 .5 +0.5 5e-2 1.E-1\n0 0.5 0.5 0.1 0.1x\n")

# --- study.yaml ---------------------------------------------------------------------------------------------
Y = "fuzz_study_yaml"
write(Y, "valid_full.yaml", """domains: [real, principled, hapke]
rock_class: 0
conf_threshold: 0.25
image_size: [1936, 1216]
models: {det-real: {trained_on: real}, det-hapke: {trained_on: hapke}}
registration: {method: consensus, seed: 0}
""")
write(Y, "valid_block_style.yaml", "domains:\n  - real\n  - synth\nregistration:\n  method: cpd\n  seed: 7\n")
write(Y, "empty.yaml", "")
write(Y, "bom.yaml", BOM + "rock_class: 0\n")
write(Y, "duplicate_keys.yaml", "rock_class: 0\nrock_class: 1\nconf_threshold: 0.2\nconf_threshold: 0.9\n")
write(Y, "extra_documents.yaml", "rock_class: 0\n---\nrock_class: 1\n---\n[1, 2]\n")
write(Y, "huge_integers.yaml", "rock_class: 99999999999999999999\nimage_size: [4294967296, -1]\n")
write(Y, "overflow_1e309.yaml", "conf_threshold: 1e309\nimage_size: [.inf, .nan]\n")
write(Y, "wrong_types.yaml", "domains: real\nrock_class: [0]\nmodels: [a, b]\nregistration: {method: bogus, seed: x}\n")
write(Y, "unknown_keys.yaml", "rock_clas: 0\nregistration: {methd: cpd}\n")
write(Y, "deep_flow.yaml", "domains: " + nested(20000, "a") + "\n")
write(Y, "deep_flow_map.yaml", "models: " + "{a: " * 20000 + "b" + "}" * 20000 + "\n")
write(Y, "deep_block_map.yaml", "".join("  " * i + "k%d:\n" % i for i in range(400)) + "  " * 400 + "v\n")
write(Y, "aliases.yaml", "a: &a [x, x, x, x]\nb: &b [*a, *a, *a, *a]\nc: &c [*b, *b, *b, *b]\ndomains: *c\n")
write(Y, "tags_and_binary.yaml", "rock_class: !!str 0\nconf_threshold: !!binary aGVsbG8=\nmodels: !custom {}\n")
write(Y, "long_token.yaml", "domains: [" + "r" * 100000 + "]\n" + "k" * 50000 + ": 1\n")
write(Y, "not_a_mapping.yaml", "- rock_class\n- 0\n")
write(Y, "invalid_yaml.yaml", "domains: [real, synth\nrock_class: : :\n\t- tab\n")
write(Y, "non_scalar_key.yaml", "? [a, b]\n: 1\n{x: 1}: 2\n")
write(Y, "model_setting_typo.yaml", "models:\n  det-real:\n    traind_on: real\n  det-b: {trained_on: real, epochs: 3}\n")
write(Y, "trained_on_null.yaml", "models: {a: {trained_on: null}, b: {trained_on: ~}, c: {trained_on: }, d: {trained_on: ''}}\n")
write(Y, "registration_out_of_range.yaml", "registration: {seed: -1, gate: 0, trials: -3}\nregistration2: {gate: .inf}\n")

# --- pairs/<A>__<B>/<stem>.json -----------------------------------------------------------------------------
P = "fuzz_pairs_json"
write(P, "valid.json", json.dumps({"pairs": [[0, 1], [2, 3], [5, 0]], "excluded_a": [4], "excluded_b": [7]}))
write(P, "valid_empty.json", '{"pairs": []}\n')
write(P, "valid_written.json", '{"pairs":[[0,0],[1,1],[11,11]]}\n')
write(P, "deep_pairs_66k.json", '{"pairs": ' + nested(DEEP) + "}")
write(P, "deep_pair_66k.json", '{"pairs": [' + nested(DEEP) + "]}")
write(P, "deep_excluded_66k.json", '{"pairs": [], "excluded_a": [' + nested(DEEP) + "]}")
write(P, "deep_object_66k.json", '{"pairs": [], "x": ' + '{"a":' * DEEP + "0" + "}" * DEEP + "}")
write(P, "huge_integers.json", '{"pairs": [[4294967296, 0], [18446744073709551615, 1], [-9223372036854775808, 2]]}')
write(P, "huge_excluded.json", '{"pairs": [], "excluded_a": [4294967296], "excluded_b": [99999999999999999999999]}')
write(P, "overflow_1e309.json", '{"pairs": [[1e309, 0]]}')
write(P, "float_indices.json", '{"pairs": [[0.5, 1], [1e2, 0], [2.0, 3]]}')
write(P, "bom.json", BOM + '{"pairs": [[0, 1]]}')
write(P, "unknown_key.json", '{"pairs": [[0, 1]], "exclude_a": [2]}')
write(P, "duplicate_keys.json", '{"pairs": [], "pairs": [[0, 0], [0, 1]]}')
write(P, "paired_twice.json", '{"pairs": [[0, 1], [0, 2]]}')
write(P, "out_of_range.json", '{"pairs": [[16, 0], [0, 12], [-1, 0]]}')
write(P, "wrong_shapes.json", '{"pairs": [[0], [0, 1, 2], "0,1", {"a": 0}, null]}')
write(P, "not_an_object.json", "[[0, 1]]")
write(P, "long_string.json", '{"pairs": "' + "x" * 100000 + '"}')
write(P, "long_number.json", '{"pairs": [[1' + "0" * 100000 + ', 0]]}')
write(P, "truncated.json", '{"pairs": [[0, 1], [2')
write(P, "trailing_garbage.json", '{"pairs": []} {"pairs": [[0, 0]]}')
write(P, "empty.json", "")
write(P, "invalid_utf8.json", b'{"pairs": [], "\xff\xfe": 1}')
# Stored boxes (fuzz_pairs_json's rocks: cx = 0.05 + 0.05 k, cy 0.5, w = h = 0.04): at their rows, moved, gone.
rock = lambda i, k: [i, 0.05 + 0.05 * k, 0.5, 0.04, 0.04]
write(P, "rocks_bound.json", json.dumps({"pairs": [[0, 1], [2, 3]], "excluded_a": [4],
                                         "rocks_a": [rock(0, 0), rock(2, 2), rock(4, 4)], "rocks_b": [rock(1, 1), rock(3, 3)]}))
write(P, "rocks_moved.json", json.dumps({"pairs": [[20, 1]], "rocks_a": [rock(20, 5)], "rocks_b": [rock(1, 11)]}))
write(P, "rocks_gone.json", json.dumps({"pairs": [[0, 1]], "rocks_a": [[0, 0.9, 0.9, 0.01, 0.01]], "rocks_b": [rock(1, 1)]}))
write(P, "rocks_bad_shapes.json", '{"pairs": [[0, 1]], "rocks_a": [[0], [0, "x", 1, 1, 1], [1e400, 0, 0, 0, 0]], "rocks_b": {}}')
write(P, "rocks_missing_box.json", json.dumps({"pairs": [[0, 1]], "rocks_a": [], "rocks_b": [rock(1, 1)]}))
write(P, "duplicate_nested_keys.json", '{"pairs": [[0, 1]], "excluded_a": [0], "excluded_a": [1], "x": {"k": 1, "k": 2}}')

# --- COCO (annotations, optionally "\n----results----\n" and the detection results) --------------------------
C = "fuzz_coco"
SEP = "\n----results----\n"
coco = {"images": [{"id": 1, "file_name": "a/scene_001.png", "width": 1936, "height": 1216},
                   {"id": 2, "file_name": "scene_002.jpg", "width": 640, "height": 480}],
        "annotations": [{"id": 1, "image_id": 1, "category_id": 3, "bbox": [100, 200, 50, 40]},
                        {"id": 2, "image_id": 2, "category_id": 3, "bbox": [0, 0, 640, 480]}],
        "categories": [{"id": 3, "name": "rock"}, {"id": 7, "name": "shadow"}]}
results = [{"image_id": 1, "category_id": 3, "bbox": [101, 199, 48, 42], "score": 0.9},
           {"image_id": 2, "category_id": 7, "bbox": [10, 10, 5, 5], "score": 0.3}]
write(C, "valid_gt.json", json.dumps(coco))
write(C, "valid_gt_results.json", json.dumps(coco) + SEP + json.dumps(results))
bad = json.loads(json.dumps(coco))
bad["annotations"].append({"id": 3, "image_id": 9, "category_id": 3, "bbox": [1, 2, 3, 4]})
bad["annotations"].append({"id": 4, "image_id": 1, "category_id": 3, "bbox": [1, 2, -3, 4]})
bad["annotations"].append({"id": 5, "image_id": 1, "category_id": 3, "bbox": [5000, 2, 3, 4]})
write(C, "bad_entries.json", json.dumps(bad))
write(C, "category_name_not_string.json", json.dumps(dict(coco, categories=[{"id": 3, "name": 5}])))
write(C, "huge_ids.json", json.dumps(coco).replace('"id": 1,', '"id": 18446744073709551615,', 1)
      .replace('"image_id": 1,', '"image_id": 4294967297,'))
write(C, "overflow_1e309.json", json.dumps(coco).replace("1936", "1e309").replace("[100, 200, 50, 40]", "[1e309, 0, 1, 1]"))
write(C, "deep_bbox_66k.json", json.dumps(coco).replace("[100, 200, 50, 40]", nested(DEEP)))
write(C, "deep_image_66k.json", json.dumps(coco).replace('"images": [', '"images": [' + nested(DEEP) + ", ", 1))
write(C, "bom.json", BOM + json.dumps(coco))
write(C, "results_not_list.json", json.dumps(coco) + SEP + '{"image_id": 1}')
write(C, "results_bad_scores.json", json.dumps(coco) + SEP +
      json.dumps([dict(results[0], score=1.5), dict(results[0], score="x"), dict(results[0], score=None)]))
write(C, "duplicate_image_ids.json", json.dumps(dict(coco, images=coco["images"] + coco["images"][:1])))
write(C, "weird_file_names.json", json.dumps(dict(coco, images=[
    {"id": 1, "file_name": "../../../escape.png", "width": 10, "height": 10},
    {"id": 2, "file_name": "", "width": 10, "height": 10},
    {"id": 3, "file_name": "/abs/dir/", "width": 10, "height": 10}])))
write(C, "not_coco.json", '{"images": {}, "annotations": [], "categories": []}')
write(C, "long_file_name.json", json.dumps(dict(coco, images=[{"id": 1, "file_name": "f" * 100000, "width": 1, "height": 1}])))
write(C, "truncated.json", json.dumps(coco)[:100])
write(C, "same_stem_two_folders.json", json.dumps(dict(coco, images=[
    {"id": 1, "file_name": "cam1/0001.png", "width": 1936, "height": 1216},
    {"id": 2, "file_name": "cam2/0001.png", "width": 640, "height": 480}])))
write(C, "same_stem_two_extensions.json", json.dumps(dict(coco, images=[
    {"id": 1, "file_name": "0001.png", "width": 1936, "height": 1216},
    {"id": 2, "file_name": "0001.jpg", "width": 640, "height": 480}])))
write(C, "image_named_classes.json", json.dumps(dict(coco, images=[
    {"id": 1, "file_name": "classes.png", "width": 1936, "height": 1216}, coco["images"][1]])))
write(C, "duplicate_category_id.json", json.dumps(dict(coco, categories=coco["categories"] + [{"id": 3, "name": "stone"}])))
write(C, "duplicate_keys.json", json.dumps(coco)[:-1] + ', "images": []}')
# COCO with segmentations: polygons and run-length masks (plain and compressed counts) in GT and results.
seg = dict(coco, images=[{"id": 1, "file_name": "s1.png", "width": 4, "height": 4}],
           annotations=[{"id": 1, "image_id": 1, "category_id": 3, "bbox": [0, 0, 4, 4],
                         "segmentation": {"counts": [3, 5, 2, 6], "size": [4, 4]}},
                        {"id": 2, "image_id": 1, "category_id": 3, "bbox": [0, 0, 2, 2],
                         "segmentation": [[0, 0, 2, 0, 2, 2, 0, 2]]}])
write(C, "segmentations.json", json.dumps(seg) + SEP + json.dumps(
    [{"image_id": 1, "category_id": 3, "bbox": [0, 0, 4, 4], "score": 0.5,
      "segmentation": {"counts": "3521", "size": [4, 4]}}]))
write(C, "rle_wrong_counts.json", json.dumps(seg).replace("[3, 5, 2, 6]", "[3, 5, 2, 99999999999]"))

# --- COCO run-length masks: "H W" then the counts, a JSON list or pycocotools' compressed string ----------------
R = "fuzz_rle"
write(R, "list_4x4.txt", "4 4\n[3, 5, 2, 6]")
write(R, "string_4x4.txt", "4 4\n3521")
write(R, "square_10x10.txt", "10 10\ng04600000U1")
write(R, "ring_5x5.txt", "5 5\n[6, 3, 2, 1, 1, 1, 2, 3, 6]")
write(R, "diagonal_4x4.txt", "4 4\n[0, 1, 4, 1, 10]")
write(R, "pinch_3x3.txt", "3 3\n[0, 3, 0, 1, 1, 1, 1, 2]")
write(R, "checkerboard_8x8.txt", "8 8\n[" + ", ".join(["1"] * 64) + "]")
write(R, "negative_and_huge.txt", "4 4\n[3, -5, 9223372036854775807]")
write(R, "long_string.txt", "4 4\n" + "o" * 40)
write(R, "empty_mask.txt", "4 4\n[16]")

# --- data.yaml and its split list (after "----list----"), in a folder with images/train/s1.png ----------------
Y = "fuzz_data_yaml"
LIST = "\n----list----\n"
write(Y, "valid_folders.yaml", "train: images/train\nval: images/train\nnames: [rock]\n")
write(Y, "valid_mapping.yaml", "train: images/train\nnames:\n  0: rock\n  3: shadow\n")
write(Y, "valid_list.yaml", "train: train.txt\nnames: [rock]" + LIST + "./images/train/s1.png\nimages/train/s1.png\n")
write(Y, "list_escapes.yaml", "train: train.txt\nnames: [rock]" + LIST + "../../etc/passwd\n/etc/passwd\n")
write(Y, "list_cvat.yaml", "train: train.txt\nnames: [rock]" + LIST + "data/images/train/s1.png\r\n# c\n\n")
write(Y, "list_not_pictures.yaml", "train: train.txt\nnames: [rock]" + LIST + "images/train\nlabels/train/s1.txt\n")
write(Y, "split_leaves.yaml", "train: ../../..\nnames: [rock]\n")
write(Y, "truncated.yaml", "train: images/train\nnames: [rock, sh")
write(Y, "names_bad.yaml", "train: images/train\nnames: {x: rock, 99999: y, 0: [a]}\n")
write(Y, "roboflow.yaml", "train: ../train/images\nval: ../valid/images\nnc: 1\nnames: ['rock']\nroboflow:\n  workspace: w\n")
write(Y, "not_a_mapping.yaml", "- train\n- val\n")

# --- a label file imported by ipd import yolo (beside a valid one), with and without --skip-bad-lines ------------
I = "fuzz_yolo_import"
write(I, "valid.txt", "0 0.5 0.5 0.1 0.2\n0 0.25 0.75 0.05 0.05\n")
write(I, "one_bad_line.txt", "0 0.5 0.5 0.1 0.2\n0 0.5 0.5 0.1\n# c\n")
write(I, "most_bad.txt", "0 0.5 0.5\nx\n0 1 2 3 4 5 6 7 8\n")
write(I, "unnamed_class.txt", "7 0.5 0.5 0.1 0.2\n")
write(I, "outline.txt", "0 0.1 0.1 0.3 0.1 0.2 0.3\n0 0.1 0.1 0.3 0.1 0.2\n")
write(I, "bom_crlf.txt", BOM + "0 0.5 0.5 0.1 0.2\r\nbad\r\n")
write(I, "nul.txt", "0 0.5 0.5 0.1 0.2\n\x00\x00\n")
# --- ipd import predictions: first byte even = a YOLO run's label file, odd = COCO results against a fixed --gt ---
P = "fuzz_prediction_import"
write(P, "run_valid.txt", "r0 0.5 0.5 0.1 0.2 0.9\n0 0.25 0.75 0.05 0.05 0.4\n")
write(P, "run_no_conf.txt", "r0 0.5 0.5 0.1 0.2\n")
write(P, "run_bad_lines.txt", "r0 0.5 0.5 0.1 0.2 1.7\nx\n0 0.5 0.5\n")
write(P, "run_outline.txt", "r0 0.1 0.1 0.3 0.1 0.2 0.3 0.8\n")
write(P, "coco_valid.json", "c" + json.dumps([
    {"image_id": 1, "category_id": 1, "bbox": [10, 5, 20, 10], "score": 0.9},
    {"image_id": 2, "category_id": 1, "bbox": [0, 0, 100, 50], "score": 0.2}]))
write(P, "coco_bad_entries.json", "c" + json.dumps([
    {"image_id": 9, "category_id": 1, "bbox": [10, 5, 20, 10], "score": 0.9},
    {"image_id": 1, "category_id": 7, "bbox": [10, 5, -20, 10], "score": "high"},
    {"image_id": 1, "bbox": [1e309, 0, 1, 1], "score": 0.5}]))
write(P, "coco_not_a_list.json", 'c{"annotations": []}')
write(P, "coco_deep.json", "c" + nested(DEEP))
# Found by fuzz_rle: counts that are not UTF-8 text, described in the message (not thrown on while describing).
write(R, "not_utf8_counts.txt", b"4 4\noo\xaaoo")
# Found by fuzz_rle: pieces in a row, the middle one met by both neighbours at one corner (it was left out).
write(R, "middle_piece_one_corner.txt", "8 8\n[" + ", ".join(
    ["1"] * 28 + ["2"] + ["1"] * 6 + ["0"] + ["1"] * 28) + "]")
# Found by fuzz_rle: 21 pieces joined by bridges along their pixel edges, which Clipper filled as 30 of 32 pixels.
write(R, "pieces_bridged_along_edges.txt", "8 8\n[1, 1, 2, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1, 1, 1, 1, 1, 1]")

#!/usr/bin/python3
"""Check that each real-scene pair is one picture: the clmarch scene against its GLSL shader.

Usage: pair_equivalence.py CLMARCH [--out DIR] [--size 640x360] [PAIR ...]   (default: every scenes/PAIR.yaml)

For each pair it renders scenes/PAIR.yaml with clmarch (`render --buffers`, linear float) and
shaders/PAIR.frag with the peer harness (glsl_peer --aux, linear float; $GLSL_PEER, else
$TMPDIR/clmarch-glsl-peer, which scripts/real-scene-pairs.sh builds), then compares per pixel:
  hit     share of pixels where both agree on hit/miss (clmarch: finite depth; shader: aux_hit)
  depth   |t_clmarch - t_shader| / t_shader where both hit: median, 99th percentile
  colour  mean |difference| of the colours clamped to [0, 1], and the share of pixels off by more
          than 0.05 in some channel
and writes DIR/PAIR_side.png: clmarch | shader over 4x |difference| | hit-mask disagreement (red:
only clmarch hits, green: only the shader). Exit 0 when every pair agrees on >= 99 % of the hits
and has >= 97 % of its pixels within 0.05; 1 otherwise.
Modelled on ../shared/peers/peer_equivalence.py.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.realpath(__file__))
PAIRS = sorted(n[:-5] for n in os.listdir(os.path.join(HERE, "scenes")) if n.endswith(".yaml"))


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = (int(x) for x in f.readline().split())
        scale = float(f.readline())
        ch = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4").reshape(h, w, ch)
    return data[::-1].astype(np.float64)  # PFM rows run bottom to top


def read_exr(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        sys.exit("cannot read " + path + ": " + oiio.geterror())
    names = list(inp.spec().channelnames)
    pixels = inp.read_image(format="float")
    inp.close()
    return {n: pixels[:, :, i].astype(np.float64) for i, n in enumerate(names)}


def write_png(path, rgb):
    rgb = np.clip(rgb, 0, 1)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * np.power(rgb, 1 / 2.4) - 0.055)
    img = (srgb * 255 + 0.5).astype(np.uint8)
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(img.shape[1], img.shape[0], 3, "uint8"))
    out.write_image(img)
    out.close()


def compare(name, clmarch, size, out):
    w, h = size.split("x")
    exr = os.path.join(out, name + "_cl.exr")
    subprocess.run([clmarch, "--quiet", "render", os.path.join(HERE, "scenes", name + ".yaml"), "--size", size,
                    "--no-image", "--buffers", exr], check=True)
    peer = os.environ.get("GLSL_PEER", os.path.join(os.environ.get("TMPDIR", "/tmp"), "clmarch-glsl-peer"))
    prefix = os.path.join(out, name + "_gl")
    subprocess.run([peer, "-s", os.path.join(HERE, "shaders", name + ".frag"), "-W", w, "-H", h, "-n", "1",
                    "--aux", prefix], check=True, stdout=subprocess.DEVNULL)
    cl = read_exr(exr)
    aux = read_pfm(prefix + "_aux.pfm")
    cl_hit = np.isfinite(cl["depth"])
    gl_hit = aux[:, :, 2] > 0.5
    agree = float(np.mean(cl_hit == gl_hit))
    both = cl_hit & gl_hit
    rel = np.abs(cl["depth"][both] - aux[:, :, 0][both]) / aux[:, :, 0][both]
    cl_rgb = np.clip(np.dstack([cl["R"], cl["G"], cl["B"]]), 0, 1)
    gl_rgb = np.clip(read_pfm(prefix + "_color.pfm"), 0, 1)
    diff = np.abs(cl_rgb - gl_rgb)
    off = float(np.mean(np.max(diff, axis=2) > 0.05))
    mask = np.zeros_like(cl_rgb)
    mask[cl_hit & ~gl_hit] = [1, 0, 0]
    mask[gl_hit & ~cl_hit] = [0, 1, 0]
    write_png(os.path.join(out, name + "_side.png"),
              np.vstack([np.hstack([cl_rgb, gl_rgb]), np.hstack([np.clip(4 * diff, 0, 1), mask])]))
    print(f"{name:8s} hit agree {100 * agree:7.3f}% (clmarch only {int(np.sum(cl_hit & ~gl_hit))}, shader only "
          f"{int(np.sum(gl_hit & ~cl_hit))})  depth rel diff median {np.median(rel):.2e} p99 "
          f"{np.percentile(rel, 99):.2e}  colour mean |d| {np.mean(diff):.4f}, >0.05 {100 * off:.2f}%")
    return agree >= 0.99 and off <= 0.03


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("clmarch")
    ap.add_argument("pairs", nargs="*", default=PAIRS)
    ap.add_argument("--size", default="640x360")
    ap.add_argument("--out", default=None)
    a = ap.parse_intermixed_args()
    out = a.out or tempfile.mkdtemp(prefix="pair_equivalence.")
    os.makedirs(out, exist_ok=True)
    print("images in", out)
    results = [compare(p, a.clmarch, a.size, out) for p in a.pairs]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())

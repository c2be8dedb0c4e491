#!/usr/bin/env python3
"""Writes mfv's own glTF test corpus (issues 21, 29): twelve scenes with the structure
of public sample scenes (a textured helmet, a multi-material textured helmet,
an anisotropy strength test, an IOR grid, a roughness comparison, a clearcoat
test, a sheen chair, a specular test; thin-walled transmission and refracting
volumes) and the tiny PNGs some of them use.
Nothing is copied: geometry is one triangle in a .bin that is deliberately
absent (mfv reads materials only), and the images are 4x4 PNGs written here.
Run from this folder: python3 make_corpus.py"""
import json, struct, zlib


def png(path, pixels, channels):
    """pixels: rows of tuples (one value 0..255 per channel); 8-bit PNG, colour type 0/2/6."""
    h, w = len(pixels), len(pixels[0])
    ctype = {1: 0, 3: 2, 4: 6}[channels]
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in pixels)
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, ctype, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
    open(path, "wb").write(data)


def ramp(lo, hi, n=16):
    return [round(lo + (hi - lo) * k / (n - 1)) for k in range(n)]


def grid4(values_per_channel):
    """4x4 image whose channel c takes values_per_channel[c][k] at texel k."""
    return [[tuple(ch[4 * y + x] for ch in values_per_channel) for x in range(4)] for y in range(4)]


def scene(materials, images=(), extensions_used=(), textures=None):
    doc = {
        "asset": {"version": "2.0", "generator": "microfacet-verify tests/data/corpus/make_corpus.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": i} for i in range(len(materials))]}],
        "buffers": [{"byteLength": 36, "uri": "absent.bin"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "materials": materials,
    }
    if images:
        doc["images"] = [{"uri": u} for u in images]
        doc["textures"] = textures or [{"source": i} for i in range(len(images))]
    if extensions_used:
        doc["extensionsUsed"] = list(extensions_used)
    return doc


def tex(i):
    return {"index": i}


def write(name, doc):
    with open(name, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    # Images: metallic-roughness (G roughness 0.2..0.9, B metallic 0..1), an sRGB albedo, a
    # roughness-only map, an anisotropy map (B strength 0.25..1), a specular map (A 0.5..1).
    z = [0] * 16
    png("mr.png", grid4([z, ramp(51, 230), ramp(0, 255)]), 3)
    png("albedo.png", grid4([ramp(40, 200), ramp(20, 120), ramp(10, 60)]), 3)
    png("rough_only.png", grid4([z, ramp(128, 255), [0] * 16]), 3)
    png("aniso.png", grid4([[255] * 16, [128] * 16, ramp(64, 255)]), 3)
    png("specular.png", grid4([[255] * 16, [255] * 16, [255] * 16, ramp(128, 255)]), 4)
    png("sheen_rough.png", grid4([z, z, z, ramp(0, 204)]), 4)  # A: sheen roughness 0..0.8

    # 1. a damaged-helmet-like textured PBR material (albedo, metal-rough, normal, occlusion, emissive)
    write("helmet.gltf", scene(
        [{"name": "helmet", "pbrMetallicRoughness": {"baseColorTexture": tex(0), "metallicRoughnessTexture": tex(1)},
          "normalTexture": tex(2), "occlusionTexture": tex(1), "emissiveTexture": tex(3), "emissiveFactor": [1, 1, 1]}],
        images=["albedo.png", "mr.png", "helmet_normal.png", "helmet_emissive.png"]))

    # 2. a flight-helmet-like scene: several textured materials, some images absent, glass lenses
    mats = []
    for i, (name, rough) in enumerate([("leather", 1.0), ("metal parts", 0.6), ("rubber", 1.0), ("wood", 0.8),
                                       ("hose", 0.9)]):
        mats.append({"name": name, "pbrMetallicRoughness": {
            "baseColorTexture": tex(0), "metallicRoughnessTexture": tex(1 + i % 3), "roughnessFactor": rough}})
    mats.append({"name": "lenses", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.95, 1, 0.3],
                 "metallicFactor": 0, "roughnessFactor": 0.05},
                 "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                "KHR_materials_volume": {"thicknessFactor": 0.002}}})
    write("flight.gltf", scene(mats, images=["albedo.png", "mr.png", "flight_rubber_mr.png", "flight_wood_mr.png"],
                               extensions_used=["KHR_materials_transmission", "KHR_materials_volume"]))

    # 3. an anisotropy strength test: strength 0, 0.5, 1, and a strength texture
    write("aniso_strength.gltf", scene(
        [{"name": f"strength {s}", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": s}}} for s in (0.0, 0.5, 1.0)] +
        [{"name": "strength texture", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.0, "anisotropyTexture": tex(0)}}}],
        images=["aniso.png"], extensions_used=["KHR_materials_anisotropy"]))

    # 4. an IOR test grid: dielectrics at several ior and roughness
    write("ior_grid.gltf", scene(
        [{"name": f"ior {ior} rough {r}", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.2, 1],
          "metallicFactor": 0, "roughnessFactor": r}, "extensions": {"KHR_materials_ior": {"ior": ior}}}
         for ior in (1.0, 1.33, 2.0) for r in (0.1, 0.5)], extensions_used=["KHR_materials_ior"]))

    # 5. a roughness comparison: dielectric and metal rows over roughness, one textured
    rows = [{"name": f"{'metal' if m else 'dielectric'} {r}", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": m, "roughnessFactor": r}}
        for m in (0.0, 1.0) for r in (0.0, 0.5, 1.0)]
    rows.append({"name": "textured roughness", "pbrMetallicRoughness": {"metallicFactor": 1.0,
                 "metallicRoughnessTexture": tex(0)}})
    write("roughness.gltf", scene(rows, images=["rough_only.png"]))

    # 6. a clearcoat test
    write("clearcoat.gltf", scene(
        [{"name": f"coat {c} rough {r}", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.1, 0.1, 1],
          "metallicFactor": 0.0, "roughnessFactor": 0.6},
          "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": c, "clearcoatRoughnessFactor": r}}}
         for c, r in ((1.0, 0.0), (0.5, 0.3))], extensions_used=["KHR_materials_clearcoat"]))

    # 7. a sheen chair: fabric with sheen, wood and metal legs
    write("sheen_chair.gltf", scene(
        [{"name": "fabric", "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.3, 0.6, 1], "metallicFactor": 0,
          "roughnessFactor": 0.9, "baseColorTexture": tex(0)},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.8, 0.8, 1.0], "sheenRoughnessFactor": 0.4}}},
         {"name": "wood", "pbrMetallicRoughness": {"baseColorTexture": tex(0), "metallicFactor": 0,
          "roughnessFactor": 0.7}},
         {"name": "legs", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1], "metallicFactor": 1,
          "roughnessFactor": 0.35}}],
        images=["chair_fabric.png"], extensions_used=["KHR_materials_sheen"]))

    # 8. a specular test: specularFactor, specularColorFactor (one above 1/f0: the spec's clamp), a texture
    write("specular.gltf", scene(
        [{"name": "half specular", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_specular": {"specularFactor": 0.5}}},
         {"name": "tinted", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_specular": {"specularColorFactor": [1.0, 0.5, 0.25]}}},
         {"name": "over one", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_specular": {"specularColorFactor": [25, 1, 1]}}},
         {"name": "textured specular", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_specular": {"specularTexture": tex(0)}}}],
        images=["specular.png"], extensions_used=["KHR_materials_specular"]))

    # 9. sheen (issue 21, the Charlie lobe checked): velvet over a dark dielectric, a red sheen over
    #    chrome, a textured sheen roughness down to 0 (the 1e-3 floor), and a sheen over an anisotropic base
    write("sheen.gltf", scene(
        [{"name": "velvet", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.1, 0.3, 1], "metallicFactor": 0,
          "roughnessFactor": 0.8},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5}}},
         {"name": "red sheen chrome", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 1,
          "roughnessFactor": 0.5},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.0, 0.0], "sheenRoughnessFactor": 0.3}}},
         {"name": "textured sheen roughness", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.6},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.5], "sheenRoughnessFactor": 1.0,
                                                 "sheenRoughnessTexture": tex(0)}}},
         {"name": "sheen off", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.6},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0, 0, 0], "sheenRoughnessFactor": 0.5}}}],
        images=["sheen_rough.png"], extensions_used=["KHR_materials_sheen"]))

    # 10. clearcoat over an anisotropic base (issue 21: both lobes): brushed metal under a coat
    write("coat_aniso.gltf", scene(
        [{"name": "coated brushed metal", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1],
          "metallicFactor": 1, "roughnessFactor": 0.5},
          "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8},
                         "KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.3}}}],
        extensions_used=["KHR_materials_anisotropy", "KHR_materials_clearcoat"]))

    # 11. thin-walled transmission (issue 29: KHR_materials_transmission without a volume): a clear
    #     film (white, full transmission: R + T = the F = 1 albedo), a frosted film at ior 1.33, a
    #     tinted half-transmitting sheet (energy R + T <= 1 may fail: fresnel_mix's diffuse gain)
    write("transmission.gltf", scene(
        [{"name": "clear film", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}},
         {"name": "frosted film", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.7},
          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                         "KHR_materials_ior": {"ior": 1.33}}},
         {"name": "tinted sheet", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.8, 0.9, 1],
          "metallicFactor": 0, "roughnessFactor": 0.5},
          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}}}],
        extensions_used=["KHR_materials_transmission", "KHR_materials_ior"]))

    # 12. refracting boundaries (issue 29: KHR_materials_transmission with KHR_materials_volume
    #     thickness > 0, checked as the rough dielectric BSDF at eta = ior): glass and water
    write("volume.gltf", scene(
        [{"name": "rough glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                         "KHR_materials_volume": {"thicknessFactor": 0.5}}},
         {"name": "water", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                         "KHR_materials_volume": {"thicknessFactor": 1.0},
                         "KHR_materials_ior": {"ior": 1.33}}}],
        extensions_used=["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior"]))


if __name__ == "__main__":
    main()

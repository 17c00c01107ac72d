"""Render an sss scene (docs/scene-format.md) in Blender 3.4, headless, with Cycles or EEVEE.

    blender -b --factory-startup --python-exit-code 1 --python tools/blender/render_scene.py -- SCENE.json \\
        --engine cycles|eevee -o OUT.exr [--width W --height H] [--time T] [--samples N] [--medium albedo|exact]
        [--sss PATH]

The output is scored against sss's ground truth by `sss eval SCENE.json --images NAME=OUT_PATTERN`
(docs/eval.md); docs/blender.md summarises the mapping below and what it measures.

Geometry, camera and materials come from `sss export gltf` (run here with the sss binary: --sss, $SSS,
`sss` on PATH, or build/sss of this checkout): world-space meshes posed at --time, the camera's frame
and vertical field of view, and each subsurface material's coefficients. Lights and the environment come
from the scene file. Mapping:

 - Medium (--medium albedo, the default). Cycles' random walk (Chiang et al. 2016) takes a colour A and a
   radius r per channel and makes volume coefficients of them (Blender 3.4,
   intern/cycles/kernel/closure/bssrdf.h and integrator/subsurface_random_walk.h): the single-scattering
   albedo alpha = remap(A), a fit made so that a semi-infinite slab reflects A, and the extinction
   sigma_t = 1 / (r sqrt(3 (1 - alpha'))), alpha' the classical dipole's albedo of total reflectance A
   under the subsurface IOR, so that r is the diffuse mean free path. Given here: A = the material's total
   diffuse reflectance (its PBD profile's, the glTF base colour), r = 1 / sigma_tr, sigma_tr =
   sqrt(3 sigma_a sigma_t'), IOR = eta. The walk leaves the medium at its first boundary hit (no
   reflection inside the interface), which is why its own alpha is needed: on a semi-infinite Skin1 slab
   lit head-on it reflects the reference's light within 2% per channel.
   --medium exact instead inverts both mappings so that the walk runs in the medium's own
   sigma_t = sigma_a + sigma_s and alpha = sigma_s / sigma_t: the same slab then reflects 1.36/1.72/1.96x
   the reference's light, the total reflectance PBD gives for an index-matched boundary (eta = 1), since
   the walk's boundary lets every path out. EEVEE receives the same colour and radius.
 - Interface: (1 - F) subsurface + F mirror (Glossy, sharp), F the dielectric Fresnel of eta, except on
   camera rays, which see the subsurface part only: sss reference leaves the camera ray's own mirror
   reflection out by default (docs/reference.md, --specular).
 - Diffuse materials: a Lambertian Diffuse BSDF of their reflectance.
 - Lights: point and spot intensity I (W/sr) -> power 4 pi I (W): Blender's point light of power P has
   intensity P / (4 pi) (checked: 4 pi W at 1 unit lights a white Lambertian plane to radiance 1/pi in
   Cycles); radius 0 (a point). Spot: size 2 x cone_angle, blend (cos(angle - delta) - cos(angle)) /
   (1 - cos(angle)) (Blender's smoothstep edge, not PBRT's f^4: approximate). Directional: a sun of
   strength = the irradiance at normal incidence, angle 0. Environment: the world shader evaluates the
   map at the scene's own lat-long mapping (docs/scene-format.md) times `scale`. Area lights and albedo
   textures are not mapped: the script refuses them.
 - Film: a box filter one pixel wide (the reference integrates each pixel's area), no denoising, scene-
   linear EXR/HDR (PNG: sRGB through the Standard view at the scene's exposure, the convention of
   `sss eval --images`). Cycles: --samples per pixel, up to 16 bounces of every kind (the reference's full
   transport), a fixed random seed.
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import bpy


class Refused(Exception):
    pass


def parse_args(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    opts = {"engine": "cycles", "out": None, "width": 0, "height": 0, "time": 0.0, "samples": 128, "sss": None,
            "medium": "albedo"}
    scene = None
    i = 0
    while i < len(args):
        a = args[i]
        if a in ("--engine", "-o", "--output", "--width", "--height", "--time", "--samples", "--sss", "--medium"):
            if i + 1 >= len(args):
                raise Refused("%s needs a value" % a)
            v = args[i + 1]
            key = {"-o": "out", "--output": "out"}.get(a, a[2:])
            opts[key] = v if key in ("engine", "out", "sss", "medium") else (float(v) if key == "time" else int(v))
            i += 2
        elif a.startswith("-"):
            raise Refused("unknown option %s" % a)
        else:
            if scene:
                raise Refused("one scene file, got %s and %s" % (scene, a))
            scene = a
            i += 1
    if not scene or not opts["out"]:
        raise Refused("usage: blender -b --python render_scene.py -- SCENE.json --engine cycles|eevee -o OUT.exr")
    if opts["engine"] not in ("cycles", "eevee"):
        raise Refused("--engine must be cycles or eevee, got %s" % opts["engine"])
    if opts["medium"] not in ("albedo", "exact"):
        raise Refused("--medium must be albedo or exact, got %s" % opts["medium"])
    if os.path.splitext(opts["out"])[1].lower() not in (".exr", ".hdr", ".png"):
        raise Refused("%s: the output must be .exr, .hdr or .png" % opts["out"])
    return scene, opts


def find_sss(given):
    here = os.path.dirname(os.path.abspath(__file__))
    for c in (given, os.environ.get("SSS"), shutil.which("sss"), os.path.join(here, "..", "..", "build", "sss")):
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    raise Refused("no sss binary: give --sss PATH or set $SSS")


# ---- The glTF export (sss export gltf) ----------------------------------------------------------

def read_glb(path):
    data = open(path, "rb").read()
    if data[:4] != b"glTF":
        raise Refused("%s: not a binary glTF" % path)
    jlen = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + jlen])
    blen = struct.unpack_from("<I", data, 20 + jlen)[0]
    return doc, data[28 + jlen:28 + jlen + blen]


def accessor(doc, binary, index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    comps = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]
    fmt = {5126: "f", 5125: "I"}[a["componentType"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    flat = struct.unpack_from("<%d%s" % (a["count"] * comps, fmt), binary, start)
    return [flat[i:i + comps] for i in range(0, len(flat), comps)] if comps > 1 else list(flat)


# ---- Cycles' random-walk parameters (Blender 3.4) --------------------------------------------------

def cycles_alpha(A):
    """subsurface_random_walk_remap at g = 0: the single-scattering albedo of the colour A."""
    a, b, c, d, e, f = 1.8260523782, 4.98511194385 + 0.127355959438, 1.09686102424, 0.496310210422, \
        4.23190299701 + 0.00310603949088, 2.40602999408
    blend = A ** 0.25
    alpha = (1 - blend) * a * math.atan(b * A) ** c + blend * d * math.atan(e * A) ** f
    return min(max(alpha, 0.0), 0.999999)


def invert(fn, target, lo=1e-6, hi=0.999999):
    """x in [lo, hi] with fn(x) = target for an increasing fn (bisection)."""
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if fn(mid) < target else (lo, mid)
    return 0.5 * (lo + hi)


def dipole_alpha_prime(rd, eta):
    """bssrdf_dipole_compute_alpha_prime: Cycles' 12-step bisection of the dipole's total reflectance."""
    inv = 1.0 / eta
    f_dr = inv * (-1.440 * inv + 0.710) + 0.668 + 0.0636 * eta
    k = (4.0 / 3.0) * (1 + f_dr) / (1 - f_dr)
    if rd < 1e-4:
        return 0.0
    if rd >= 0.995:
        return 0.999999
    x0, x1, xm = 0.0, 1.0, 0.5
    for _ in range(12):
        xm = 0.5 * (x0 + x1)
        s = math.sqrt(3 * (1 - xm))
        f = 0.5 * xm * (1 + math.exp(-k * s)) * math.exp(-s)
        x0, x1 = (xm, x1) if f < rd else (x0, xm)
    return xm


def albedo_inputs(sigma_t, alpha, g, rho_eff):
    """Colour = the material's total diffuse reflectance, radius = its diffuse mean free path."""
    radius = [1.0 / math.sqrt(3 * st * (1 - al) * st * (1 - g * al)) for st, al in zip(sigma_t, alpha)]
    return [min(max(r, 1e-6), 1.0) for r in rho_eff], radius


def exact_inputs(sigma_t, alpha, eta):
    """Colour and radius per channel that make Cycles' walk use sigma_t and alpha."""
    colour, radius = [], []
    for st, al in zip(sigma_t, alpha):
        A = invert(cycles_alpha, min(al, 0.999998))
        ap = dipole_alpha_prime(A, eta)
        colour.append(A)
        radius.append(1.0 / (st * math.sqrt(3 * max(1 - ap, 1e-12))))
    return colour, radius


def medium_of(material):
    """sigma_t, alpha, g, eta of an exported subsurface material (src/export/gltf.c add_material)."""
    ext = material["extensions"]
    vol, sc = ext["KHR_materials_volume"], ext["KHR_materials_volume_scatter"]
    max_t = 1.0 / vol["attenuationDistance"]
    sigma_t = [-math.log(c) * max_t for c in vol["attenuationColor"]]
    g = sc.get("scatterAnisotropy", 0.0)

    def multiscatter(al):  # the exporter's fit, increasing in alpha
        s = math.sqrt((1 - al) / (1 - g * al))
        return (1 - s) * (1 - 0.139 * s) / (1 + 1.17 * s)
    alpha = [invert(multiscatter, rho, 0.0, 1.0) for rho in sc["multiscatterColor"]]
    return sigma_t, alpha, g, ext["KHR_materials_ior"]["ior"]


# ---- Blender scene -------------------------------------------------------------------------------

def node(nt, kind, **inputs):
    n = nt.nodes.new(kind)
    for k, v in inputs.items():
        n.inputs[k].default_value = v
    return n


def subsurface_material(name, gltf_mat, mode):
    sigma_t, alpha, g, eta = medium_of(gltf_mat)
    if mode == "exact":
        colour, radius = exact_inputs(sigma_t, alpha, eta)
    else:
        colour, radius = albedo_inputs(sigma_t, alpha, g, gltf_mat["pbrMetallicRoughness"]["baseColorFactor"][:3])
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.use_sss_translucency = True  # EEVEE: light through thin parts
    nt = mat.node_tree
    nt.nodes.clear()
    sss = node(nt, "ShaderNodeSubsurfaceScattering", Color=colour + [1.0], Scale=1.0, Radius=radius, IOR=eta,
               Anisotropy=g)
    sss.falloff = "RANDOM_WALK"
    mirror = node(nt, "ShaderNodeBsdfGlossy", Color=(1, 1, 1, 1), Roughness=0.0)
    mirror.distribution = "SHARP"
    fresnel = node(nt, "ShaderNodeFresnel", IOR=eta)
    path = nt.nodes.new("ShaderNodeLightPath")
    no_mirror = node(nt, "ShaderNodeMath")  # F on every ray but the camera's
    no_mirror.operation = "MULTIPLY"
    nt.links.new(fresnel.outputs[0], no_mirror.inputs[0])
    invert_cam = node(nt, "ShaderNodeMath")
    invert_cam.operation = "SUBTRACT"
    invert_cam.inputs[0].default_value = 1.0
    nt.links.new(path.outputs["Is Camera Ray"], invert_cam.inputs[1])
    nt.links.new(invert_cam.outputs[0], no_mirror.inputs[1])
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(no_mirror.outputs[0], mix.inputs[0])
    nt.links.new(sss.outputs[0], mix.inputs[1])
    nt.links.new(mirror.outputs[0], mix.inputs[2])
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(mix.outputs[0], out.inputs[0])
    return mat


def diffuse_material(name, gltf_mat):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    base = gltf_mat.get("pbrMetallicRoughness", {}).get("baseColorFactor", [0.8, 0.8, 0.8, 1])
    d = node(nt, "ShaderNodeBsdfDiffuse", Color=list(base[:3]) + [1.0], Roughness=0.0)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(d.outputs[0], out.inputs[0])
    return mat


def add_meshes(doc, binary, mode):
    mats = []
    for i, m in enumerate(doc.get("materials", [])):
        if "baseColorTexture" in m.get("pbrMetallicRoughness", {}):
            raise Refused("materials[%d]: albedo textures are not mapped to Blender by this script" % i)
        sub = "KHR_materials_volume" in m.get("extensions", {})
        mats.append(subsurface_material("m%d" % i, m, mode) if sub else diffuse_material("m%d" % i, m))
    for n, nd in enumerate(doc["nodes"]):
        if "mesh" not in nd:
            continue
        if any(abs(v - (1.0 if k % 5 == 0 else 0.0)) > 1e-9 for k, v in enumerate(nd.get("matrix", [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]))):
            raise Refused("nodes[%d]: the export's meshes are in world space; a node matrix is unexpected" % n)
        for p, prim in enumerate(doc["meshes"][nd["mesh"]]["primitives"]):
            pos = accessor(doc, binary, prim["attributes"]["POSITION"])
            nrm = accessor(doc, binary, prim["attributes"]["NORMAL"])
            idx = accessor(doc, binary, prim["indices"])
            me = bpy.data.meshes.new("mesh%d_%d" % (n, p))
            me.from_pydata(pos, [], [idx[k:k + 3] for k in range(0, len(idx), 3)])
            me.polygons.foreach_set("use_smooth", [True] * len(me.polygons))
            me.use_auto_smooth = True  # the shading normals of the scene (custom split normals)
            me.normals_split_custom_set_from_vertices(nrm)
            me.materials.append(mats[prim["material"]])
            bpy.context.scene.collection.objects.link(bpy.data.objects.new(me.name, me))


def add_camera(doc, width, height):
    cam_node = next(nd for nd in doc["nodes"] if "camera" in nd)
    m = cam_node["matrix"]  # column-major, glTF: the camera looks down its -z with +y up, as Blender's
    cd = bpy.data.cameras.new("camera")
    cd.sensor_fit = "VERTICAL"
    cd.angle_y = doc["cameras"][cam_node["camera"]]["perspective"]["yfov"]
    cd.clip_start = 1e-3
    cd.clip_end = 1e6
    obj = bpy.data.objects.new("camera", cd)
    from mathutils import Matrix
    obj.matrix_world = Matrix([[m[c * 4 + r] for c in range(4)] for r in range(4)])
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj


def rgb(v):
    return [float(v)] * 3 if isinstance(v, (int, float)) else [float(c) for c in v]


def add_light(i, l):
    kind = l["type"]
    if kind in ("point", "spot"):
        ld = bpy.data.lights.new("light%d" % i, "POINT" if kind == "point" else "SPOT")
        I = rgb(l["intensity"])
        peak = max(I)
        ld.energy = 4 * math.pi * peak
        ld.color = [c / peak if peak > 0 else 1.0 for c in I]
        ld.shadow_soft_size = 0.0
        obj = bpy.data.objects.new(ld.name, ld)
        obj.location = l["position"]
        if kind == "spot":
            angle, delta = math.radians(l["cone_angle"]), math.radians(l.get("cone_delta", 0.0))
            ld.spot_size = 2 * angle
            ld.spot_blend = (math.cos(angle - delta) - math.cos(angle)) / (1 - math.cos(angle))
            aim(obj, [l["look_at"][k] - l["position"][k] for k in range(3)])
    elif kind == "directional":
        ld = bpy.data.lights.new("light%d" % i, "SUN")
        E = rgb(l["radiance"])
        peak = max(E)
        ld.energy = peak
        ld.color = [c / peak if peak > 0 else 1.0 for c in E]
        ld.angle = 0.0
        obj = bpy.data.objects.new(ld.name, ld)
        aim(obj, l["direction"])
    else:
        raise Refused("lights[%d]: %s lights are not mapped to Blender by this script" % (i, kind))
    bpy.context.scene.collection.objects.link(obj)


def aim(obj, direction):
    from mathutils import Vector
    obj.rotation_euler = Vector(direction).to_track_quat("-Z", "Y").to_euler()


def set_world(scene_dir, lights):
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    nt = world.node_tree
    bg = nt.nodes["Background"]
    env = [l for l in lights if l["type"] == "environment"]
    if len(env) > 1:
        raise Refused("more than one environment light")
    if not env:
        bg.inputs["Color"].default_value = (0, 0, 0, 1)
    else:
        e = env[0]
        path = e["file"] if os.path.isabs(e["file"]) else os.path.join(scene_dir, e["file"])
        # docs/scene-format.md: m(u, v) = (sin t sin p, cos t, -sin t cos p), p = 2 pi (u - 0.5) - rotate_y,
        # t = pi v, v = 0 at the zenith (+y); Blender's image v runs up: (u, 1 - v)
        coord = nt.nodes.new("ShaderNodeTexCoord")
        sep = nt.nodes.new("ShaderNodeSeparateXYZ")
        nt.links.new(coord.outputs["Generated"], sep.inputs[0])
        neg_z = node(nt, "ShaderNodeMath")
        neg_z.operation = "MULTIPLY"
        neg_z.inputs[1].default_value = -1.0
        nt.links.new(sep.outputs["Z"], neg_z.inputs[0])
        phi = node(nt, "ShaderNodeMath")
        phi.operation = "ARCTAN2"
        nt.links.new(sep.outputs["X"], phi.inputs[0])
        nt.links.new(neg_z.outputs[0], phi.inputs[1])
        u = node(nt, "ShaderNodeMath")
        u.operation = "MULTIPLY_ADD"
        u.inputs[1].default_value = 1.0 / (2 * math.pi)
        u.inputs[2].default_value = 0.5 + math.radians(e.get("rotate_y", 0.0)) / (2 * math.pi)
        nt.links.new(phi.outputs[0], u.inputs[0])
        theta = node(nt, "ShaderNodeMath")
        theta.operation = "ARCCOSINE"
        nt.links.new(sep.outputs["Y"], theta.inputs[0])
        v = node(nt, "ShaderNodeMath")
        v.operation = "MULTIPLY_ADD"
        v.inputs[1].default_value = -1.0 / math.pi
        v.inputs[2].default_value = 1.0
        nt.links.new(theta.outputs[0], v.inputs[0])
        uv = nt.nodes.new("ShaderNodeCombineXYZ")
        nt.links.new(u.outputs[0], uv.inputs[0])
        nt.links.new(v.outputs[0], uv.inputs[1])
        tex = nt.nodes.new("ShaderNodeTexImage")
        tex.image = bpy.data.images.load(path)
        tex.extension = "REPEAT"
        tex.interpolation = "Linear"
        nt.links.new(uv.outputs[0], tex.inputs["Vector"])
        scale = node(nt, "ShaderNodeVectorMath")
        scale.operation = "MULTIPLY"
        scale.inputs[1].default_value = e.get("scale", [1, 1, 1])
        nt.links.new(tex.outputs["Color"], scale.inputs[0])
        nt.links.new(scale.outputs[0], bg.inputs["Color"])
    bg.inputs["Strength"].default_value = 1.0
    bpy.context.scene.world = world


def set_render(opts, width, height, exposure):
    s = bpy.context.scene
    s.render.resolution_x, s.render.resolution_y, s.render.resolution_percentage = width, height, 100
    s.view_settings.view_transform = "Standard"
    s.view_settings.look = "None"
    s.view_settings.gamma = 1.0
    ext = os.path.splitext(opts["out"])[1].lower()
    s.view_settings.exposure = exposure if ext == ".png" else 0.0
    fmt = s.render.image_settings
    fmt.file_format = {".exr": "OPEN_EXR", ".hdr": "HDR", ".png": "PNG"}[ext]
    fmt.color_mode = "RGB"
    if ext == ".exr":
        fmt.color_depth = "32"
    if opts["engine"] == "cycles":
        s.render.engine = "CYCLES"
        c = s.cycles
        c.device = "CPU"
        c.samples = opts["samples"]
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.seed = 0
        c.pixel_filter_type = "BOX"
        c.filter_width = 1.0
        c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 16
        c.transparent_max_bounces = 16
        c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    else:
        s.render.engine = "BLENDER_EEVEE"
        ee = s.eevee
        ee.taa_render_samples = opts["samples"]
        ee.sss_samples = 25
        ee.use_soft_shadows = False
        ee.shadow_cube_size = "2048"
        ee.shadow_cascade_size = "4096"
        s.render.filter_size = 1.0  # EEVEE's film filter width in pixels
    s.render.filepath = os.path.abspath(opts["out"])


def main():
    scene_path, opts = parse_args(sys.argv)
    desc = json.load(open(scene_path))
    cam = desc["camera"]
    width = opts["width"] or cam["width"]
    height = opts["height"] or cam["height"]
    tmp = tempfile.mkdtemp(prefix="sss_blender_")
    try:
        glb = os.path.join(tmp, "scene.glb")
        cmd = [find_sss(opts["sss"]), "export", "gltf", scene_path, "-o", glb, "--time", repr(opts["time"]),
               "--width", str(width), "--height", str(height), "-q"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise Refused("sss export gltf failed: %s" % r.stderr.strip())
        doc, binary = read_glb(glb)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    lights = desc.get("lights", [])
    for i, l in enumerate(lights):
        if l["type"] != "environment":
            add_light(i, l)
    add_meshes(doc, binary, opts["medium"])
    add_camera(doc, width, height)
    set_world(os.path.dirname(os.path.abspath(scene_path)), lights)
    set_render(opts, width, height, desc.get("render", {}).get("exposure", 0.0))
    bpy.ops.render.render(write_still=True)
    print("render_scene: wrote %s (%s, %dx%d)" % (opts["out"], opts["engine"], width, height))


if __name__ == "__main__":
    try:
        main()
    except Refused as e:
        print("render_scene: error: %s" % e, file=sys.stderr)
        sys.exit(1)

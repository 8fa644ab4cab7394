"""Reads a subdfit USD export with Pixar's usd-core and reports what a renderer would take from it.

    python read_usd.py STAGE OUT_DIR [--check]

Opens STAGE (asset.usdz or asset.usda), checks the cage's topology (UsdGeom.Mesh.ValidateTopology)
and runs every registered UsdValidation validator; then writes OUT_DIR/stage.json with the stage
metadata, the cage as USD holds it (points, topology, rules, creases, corners, holes, face-varying
primvars) and, per UsdPreviewSurface input, the texture it reads (resolved path, colour space,
scale, bias, output, primvar). Each texture's bytes, read through USD's asset resolver (so from
inside the package when that is where it resolves), go to OUT_DIR/<input>.<ext>. Prints the
validation results; exits 0 when the stage opened, whatever it found (the caller judges), or
with --check exits 1 unless the stage opened, its cage's topology is valid, no validator
reported an error and every texture resolved.
"""
import json
import os
import sys

from pxr import Ar, Sdf, Usd, UsdGeom, UsdShade, UsdValidation


def array(attribute):
    value = attribute.Get() if attribute and attribute.HasAuthoredValue() else None
    return [] if value is None else list(value)


def vectors(values):
    return [list(v) for v in values]


def texture_of(surface, input_name, out_dir):
    source = surface.GetInput(input_name)
    if not source or not source.HasConnectedSource():
        return None
    connected, output, _ = source.GetConnectedSource()
    texture = UsdShade.Shader(connected.GetPrim())
    entry = {"shader": texture.GetIdAttr().Get(), "output": output}
    file = texture.GetInput("file").Get()
    entry["asset"] = file.path
    entry["resolved"] = str(file.resolvedPath)
    for name in ("sourceColorSpace", "wrapS", "wrapT"):
        value = texture.GetInput(name).Get() if texture.GetInput(name) else None
        entry[name] = None if value is None else str(value)
    for name, fallback in (("scale", [1, 1, 1, 1]), ("bias", [0, 0, 0, 0])):
        value = texture.GetInput(name).Get() if texture.GetInput(name) else None
        entry[name] = fallback if value is None else list(value)
    st = texture.GetInput("st")
    if st and st.HasConnectedSource():
        reader, _, _ = st.GetConnectedSource()
        reader = UsdShade.Shader(reader.GetPrim())
        entry["primvar"] = reader.GetInput("varname").Get()
        entry["reader"] = reader.GetIdAttr().Get()
    if file.resolvedPath:
        asset = Ar.GetResolver().OpenAsset(Ar.ResolvedPath(str(file.resolvedPath)))
        if asset:
            extracted = os.path.join(out_dir, input_name + os.path.splitext(file.path.rstrip("]"))[1])
            with open(extracted, "wb") as f:
                f.write(asset.GetBuffer())
            entry["extracted"] = extracted
    return entry


def failures(report):
    found = []
    if not report.get("opened"):
        return ["the stage did not open"]
    found += [f"{e['name']}: {e['message']}" for e in report["validation"] if "Error" in e["type"]]
    if report.get("meshes", 0) < 1:
        found.append("no mesh")
    elif not report["cage"]["topologyValid"]:
        found.append("invalid topology: " + report["cage"]["topologyReason"])
    for name, entry in report.get("material", {}).get("inputs", {}).items():
        if "extracted" not in entry:
            found.append(f"{name}: {entry['asset']} does not resolve")
    return found


def main():
    path, out_dir = sys.argv[1], sys.argv[2]
    check = "--check" in sys.argv[3:]
    os.makedirs(out_dir, exist_ok=True)
    stage = Usd.Stage.Open(path)
    report = {"opened": bool(stage)}
    if not stage:
        json.dump(report, open(os.path.join(out_dir, "stage.json"), "w"))
        return 1 if check else 0

    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    errors = UsdValidation.ValidationContext(validators).Validate(stage)
    report["validators"] = sorted(v.GetMetadata().name for v in validators)
    report["validation"] = [{"type": str(e.GetType()), "name": str(e.GetName()), "message": e.GetMessage()} for e in errors]
    print(f"{path}: {len(validators)} UsdValidation validators, {len(errors)} findings")
    for e in errors:
        print(f"  {e.GetType()} {e.GetName()}: {e.GetMessage()}")

    report["stage"] = {"upAxis": str(UsdGeom.GetStageUpAxis(stage)),
                       "metersPerUnit": UsdGeom.GetStageMetersPerUnit(stage),
                       "hasAuthoredMetersPerUnit": UsdGeom.StageHasAuthoredMetersPerUnit(stage),
                       "defaultPrim": str(stage.GetDefaultPrim().GetPath()) if stage.GetDefaultPrim() else ""}
    meshes = [UsdGeom.Mesh(p) for p in stage.Traverse() if p.IsA(UsdGeom.Mesh)]
    report["meshes"] = len(meshes)
    if not meshes:
        json.dump(report, open(os.path.join(out_dir, "stage.json"), "w"))
        return 1 if check else 0
    mesh = meshes[0]
    counts, indices = mesh.GetFaceVertexCountsAttr().Get(), mesh.GetFaceVertexIndicesAttr().Get()
    points = mesh.GetPointsAttr().Get()
    valid, why = UsdGeom.Mesh.ValidateTopology(indices, counts, len(points))
    print(f"{mesh.GetPath()}: {len(points)} points, {len(counts)} faces, ValidateTopology: {valid} {why}")
    cage = {"path": str(mesh.GetPath()), "topologyValid": bool(valid), "topologyReason": why,
            "points": vectors(points), "faceVertexCounts": list(counts), "faceVertexIndices": list(indices),
            "subdivisionScheme": mesh.GetSubdivisionSchemeAttr().Get(),
            "interpolateBoundary": mesh.GetInterpolateBoundaryAttr().Get(),
            "faceVaryingLinearInterpolation": mesh.GetFaceVaryingLinearInterpolationAttr().Get(),
            "triangleSubdivisionRule": mesh.GetTriangleSubdivisionRuleAttr().Get(),
            "orientation": mesh.GetOrientationAttr().Get()}
    for name in ("creaseIndices", "creaseLengths", "creaseSharpnesses", "cornerIndices", "cornerSharpnesses", "holeIndices"):
        cage[name] = array(mesh.GetPrim().GetAttribute(name))
    primvars = {}
    for primvar in UsdGeom.PrimvarsAPI(mesh).GetPrimvars():
        if primvar.GetTypeName() != Sdf.ValueTypeNames.TexCoord2fArray:
            continue
        primvars[primvar.GetPrimvarName()] = {"interpolation": primvar.GetInterpolation(),
                                              "values": vectors(primvar.Get()),
                                              "indices": list(primvar.GetIndices()) if primvar.IsIndexed() else []}
    cage["primvars"] = primvars
    report["cage"] = cage

    material, _ = UsdShade.MaterialBindingAPI(mesh).ComputeBoundMaterial()
    if material:
        surface = material.ComputeSurfaceSource()[0]
        displacement = material.ComputeDisplacementSource()[0]
        report["material"] = {"path": str(material.GetPath()),
                              "surface": surface.GetIdAttr().Get() if surface else None,
                              "displacement": displacement.GetIdAttr().Get() if displacement else None,
                              "inputs": {}}
        if surface:
            for name in ("displacement", "diffuseColor", "metallic", "roughness", "occlusion", "emissiveColor", "normal"):
                entry = texture_of(surface, name, out_dir)
                if entry:
                    report["material"]["inputs"][name] = entry
    with open(os.path.join(out_dir, "stage.json"), "w") as f:
        json.dump(report, f)
    for name, entry in report.get("material", {}).get("inputs", {}).items():
        print(f"  inputs:{name} <- {entry['shader']} {entry['asset']} ({entry['sourceColorSpace']}, "
              f"{entry.get('primvar')}.{entry['output']}) resolved: {entry['resolved']}")
    problems = failures(report)
    for problem in problems:
        print(f"{path}: {problem}")
    return 1 if check and problems else 0


if __name__ == "__main__":
    sys.exit(main())

#include "io/gltf.h"

#include <tiny_gltf.h>

#include <cstring>
#include <limits>

#include "io/output_file.h"
#include "common/error.h"

namespace hdrf::io {

namespace {

// Appends raw bytes to the buffer (4-byte aligned) and returns its buffer view.
int AddView(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
  auto& buf = model.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  const std::size_t offset = buf.size();
  buf.resize(offset + bytes);
  std::memcpy(buf.data() + offset, data, bytes);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = offset;
  v.byteLength = bytes;
  v.target = target;
  model.bufferViews.push_back(v);
  return int(model.bufferViews.size() - 1);
}

int AddAccessor(tinygltf::Model& model, int view, int component, int type, std::size_t count) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.type = type;
  a.count = count;
  model.accessors.push_back(a);
  return int(model.accessors.size() - 1);
}

}  // namespace

void WriteGlb(const std::filesystem::path& file, const mesh::Atlas& atlas, const std::vector<std::uint8_t>& png,
              mesh::UpAxis up, const std::string& radiance_units) {
  const mesh::Mesh& m = atlas.mesh;
  const std::size_t nv = m.position.size();
  if (nv == 0 || m.triangles.empty()) throw Error("glTF: the mesh is empty (" + file.string() + ")");
  const auto turn = [up](Float3 p) { return up == mesh::UpAxis::kZ ? Float3{p.x, p.z, -p.y} : p; };
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "HDRFusion Studio";
  model.asset.extras = tinygltf::Value(tinygltf::Value::Object{
      {"radiance_attribute", tinygltf::Value(std::string("_RADIANCE"))},
      {"radiance_units", tinygltf::Value(radiance_units)}});
  model.buffers.resize(1);
  std::vector<float> pos(nv * 3), nor, uv(nv * 2), rad;
  std::vector<double> lo(3, std::numeric_limits<double>::max()), hi(3, -std::numeric_limits<double>::max());
  for (std::size_t v = 0; v < nv; ++v) {
    const Float3 p = turn(m.position[v]);
    const float c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k) {
      pos[3 * v + std::size_t(k)] = c[k];
      lo[std::size_t(k)] = std::min(lo[std::size_t(k)], double(c[k]));
      hi[std::size_t(k)] = std::max(hi[std::size_t(k)], double(c[k]));
    }
    const Float2 t = atlas.UvTopLeft(v);
    uv[2 * v] = t.x;
    uv[2 * v + 1] = t.y;
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  int a = AddAccessor(model, AddView(model, pos.data(), pos.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv);
  model.accessors[std::size_t(a)].minValues = lo;
  model.accessors[std::size_t(a)].maxValues = hi;
  prim.attributes["POSITION"] = a;
  if (m.normal.size() == nv) {
    nor.resize(nv * 3);
    for (std::size_t v = 0; v < nv; ++v) {
      const Float3 n = turn(m.normal[v]);
      nor[3 * v] = n.x, nor[3 * v + 1] = n.y, nor[3 * v + 2] = n.z;
    }
    prim.attributes["NORMAL"] = AddAccessor(model, AddView(model, nor.data(), nor.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv);
  }
  prim.attributes["TEXCOORD_0"] = AddAccessor(model, AddView(model, uv.data(), uv.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                              TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, nv);
  if (m.radiance.size() == nv) {
    rad.resize(nv * 3);
    for (std::size_t v = 0; v < nv; ++v) rad[3 * v] = m.radiance[v].x, rad[3 * v + 1] = m.radiance[v].y, rad[3 * v + 2] = m.radiance[v].z;
    prim.attributes["_RADIANCE"] = AddAccessor(model, AddView(model, rad.data(), rad.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv);
  }
  std::vector<std::uint32_t> idx;
  idx.reserve(m.triangles.size() * 3);
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) idx.push_back(std::uint32_t(t[std::size_t(k)]));
  prim.indices = AddAccessor(model, AddView(model, idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size());
  // The texture: PNG bytes in the binary buffer.
  if (!png.empty()) {
    tinygltf::Image img;
    img.name = "base_colour";
    img.mimeType = "image/png";
    img.bufferView = AddView(model, png.data(), png.size(), 0);
    model.bufferViews.back().target = 0;
    model.images.push_back(img);
    tinygltf::Sampler s;
    s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    s.wrapS = s.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    model.samplers.push_back(s);
    tinygltf::Texture tex;
    tex.source = 0;
    tex.sampler = 0;
    model.textures.push_back(tex);
  }
  tinygltf::Material mat;
  mat.name = "hdrfusion_scan";
  mat.pbrMetallicRoughness.metallicFactor = 0;
  mat.pbrMetallicRoughness.roughnessFactor = 1;
  if (!model.textures.empty()) mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  model.materials.push_back(mat);
  prim.material = 0;
  tinygltf::Mesh mesh;
  mesh.name = "hdrfusion_scan";
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "hdrfusion_scan";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  OutputFile out(file);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out.stream(), false, true) || !out.stream())
    throw InputError(file, "cannot be written as glTF binary (disk full?)");
  out.Commit();
}

}  // namespace hdrf::io

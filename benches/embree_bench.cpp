// Intel Embree's side of the ray-casting comparison (benches/embree.sh; shadowlab's side is
// examples/ray_bench.rs, which writes the inputs this program reads).
//
// Usage: embree_bench DIR [--threads 1,2] [--runs R] [--warmup W] [--hits]
//        embree_bench --version
//
// Reads DIR/mesh.bin and DIR/rays-{camera,random,grid}.bin (formats in examples/ray_bench.rs: f32
// positions, u32 triangles; per ray set a count, t_max and f32 origin + direction per ray). For each
// thread count N, on a device made with the config "threads=N":
//   * build: rtcCommitScene of one triangle geometry, default build quality (MEDIUM) and HIGH,
//     W untimed then R timed builds, each a new scene (the buffers are filled outside the timing);
//   * per ray set, on the default-quality scene: closest hit and any hit, each as single rays
//     (rtcIntersect1, rtcOccluded1) and as 16-wide packets (rtcIntersect16, rtcOccluded16) of
//     consecutive rays (4x4 pixel tiles in the camera and grid sets), t in [0, t_max]. The rays are
//     split into fixed chunks of 1024 (64 packets) that N std::threads take in turn from an atomic
//     counter, as rayon's workers take shadowlab's chunks. The coherent sets (camera, grid) pass
//     RTC_RAY_QUERY_FLAG_COHERENT, the random set RTC_RAY_QUERY_FLAG_INCOHERENT. Each casting thread
//     flushes denormals to zero, as Embree's documentation advises.
// Prints one JSON object: the library's version and properties, every timed run in ms, hit counts,
// and how many rays the packets answer differently from the single rays. With --hits, writes the
// single-ray answers per ray: DIR/embree-SET.closest (i32 triangle index, -1 for a miss) and
// DIR/embree-SET.anyhit (u8, 1 if occluded).
//
// Build (benches/embree.sh does it): g++ -std=c++17 -O3 -march=x86-64-v3 -pthread -I EMBREE_INCLUDE
// embree_bench.cpp LIBEMBREE4 -Wl,-rpath,LIBDIR

#include <embree4/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr size_t kChunk = 1024;  // rays per work item (shadowlab's RAY_CHUNK)
constexpr size_t kPacket = 16;
const char* const kSets[] = {"camera", "random", "grid"};

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "embree_bench: %s\n", message.c_str());
  std::exit(1);
}

void on_error(void*, RTCError code, const char* message) {
  fail("Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : ""));
}

// A whole little-endian file of 4-byte words.
struct Words {
  std::vector<uint32_t> words;
  size_t at = 0;
  std::string path;

  explicit Words(const std::string& file) : path(file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) fail("cannot open " + file);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() % 4 != 0) fail(file + " is not a whole number of 4-byte words");
    words.resize(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), bytes.size());
  }
  uint32_t u32() {
    if (at >= words.size()) fail(path + " ends early");
    return words[at++];
  }
  float f32() {
    uint32_t w = u32();
    float f;
    std::memcpy(&f, &w, 4);
    return f;
  }
  void end() const {
    if (at != words.size()) fail(path + " is longer than its counts say");
  }
};

struct Mesh {
  std::vector<float> positions;  // x, y, z per vertex
  std::vector<uint32_t> triangles;
};

struct RaySet {
  std::string name;
  float t_max = 0;
  std::vector<float> rays;  // origin, direction: 6 floats per ray
  size_t count() const { return rays.size() / 6; }
};

Mesh read_mesh(const std::string& dir) {
  Words in(dir + "/mesh.bin");
  Mesh mesh;
  uint32_t vertices = in.u32(), triangles = in.u32();
  mesh.positions.resize(size_t(vertices) * 3);
  for (float& x : mesh.positions) x = in.f32();
  mesh.triangles.resize(size_t(triangles) * 3);
  for (uint32_t& i : mesh.triangles) {
    i = in.u32();
    if (i >= vertices) fail("mesh.bin: a vertex index is out of range");
  }
  in.end();
  return mesh;
}

RaySet read_rays(const std::string& dir, const std::string& name) {
  Words in(dir + "/rays-" + name + ".bin");
  RaySet set;
  set.name = name;
  uint32_t count = in.u32();
  set.t_max = in.f32();
  set.rays.resize(size_t(count) * 6);
  for (float& x : set.rays) x = in.f32();
  in.end();
  return set;
}

// A scene of the mesh, committed with the given quality; the commit's time in ms goes to *ms.
RTCScene build_scene(RTCDevice device, const Mesh& mesh, RTCBuildQuality quality, double* ms) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, quality);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, quality);
  size_t vertices = mesh.positions.size() / 3, triangles = mesh.triangles.size() / 3;
  // Embree pads the buffers it allocates for its 16-byte vertex loads.
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
  std::copy(mesh.positions.begin(), mesh.positions.end(), v);
  auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles));
  std::copy(mesh.triangles.begin(), mesh.triangles.end(), t);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  auto start = std::chrono::steady_clock::now();
  rtcCommitScene(scene);
  *ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return scene;
}

// Runs work(begin, end) over [0, count) in chunks of kChunk on `threads` threads.
void in_chunks(size_t count, int threads, const std::function<void(size_t, size_t)>& work) {
  std::atomic<size_t> next{0};
  auto worker = [&] {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    for (size_t begin; (begin = next.fetch_add(kChunk)) < count;)
      work(begin, std::min(begin + kChunk, count));
  };
  if (threads == 1) {
    worker();
    return;
  }
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
  for (auto& thread : pool) thread.join();
}

// The answers of one query mode: the closest hit's triangle (-1 for none) or 1/0 for any hit.
using Answers = std::vector<int32_t>;

void closest_single(RTCScene scene, const RaySet& set, RTCRayQueryFlags flags, int threads,
                    Answers& out) {
  in_chunks(set.count(), threads, [&](size_t begin, size_t end) {
    RTCIntersectArguments args;
    rtcInitIntersectArguments(&args);
    args.flags = flags;
    for (size_t i = begin; i < end; ++i) {
      const float* r = &set.rays[6 * i];
      RTCRayHit rh;
      rh.ray.org_x = r[0], rh.ray.org_y = r[1], rh.ray.org_z = r[2], rh.ray.tnear = 0.0f;
      rh.ray.dir_x = r[3], rh.ray.dir_y = r[4], rh.ray.dir_z = r[5], rh.ray.time = 0.0f;
      rh.ray.tfar = set.t_max, rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &rh, &args);
      out[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : int32_t(rh.hit.primID);
    }
  });
}

void anyhit_single(RTCScene scene, const RaySet& set, RTCRayQueryFlags flags, int threads,
                   Answers& out) {
  in_chunks(set.count(), threads, [&](size_t begin, size_t end) {
    RTCOccludedArguments args;
    rtcInitOccludedArguments(&args);
    args.flags = flags;
    for (size_t i = begin; i < end; ++i) {
      const float* r = &set.rays[6 * i];
      RTCRay ray;
      ray.org_x = r[0], ray.org_y = r[1], ray.org_z = r[2], ray.tnear = 0.0f;
      ray.dir_x = r[3], ray.dir_y = r[4], ray.dir_z = r[5], ray.time = 0.0f;
      ray.tfar = set.t_max, ray.mask = ~0u, ray.id = 0, ray.flags = 0;
      rtcOccluded1(scene, &ray, &args);
      out[i] = ray.tfar == -INFINITY ? 1 : 0;
    }
  });
}

// Fills lanes [0, n) of a 16-wide packet from rays [first, first + n); the other lanes are invalid.
void fill_packet(RTCRay16& p, int valid[kPacket], const RaySet& set, size_t first, size_t n) {
  for (size_t k = 0; k < kPacket; ++k) {
    valid[k] = k < n ? -1 : 0;
    const float* r = &set.rays[6 * (first + std::min(k, n - 1))];
    p.org_x[k] = r[0], p.org_y[k] = r[1], p.org_z[k] = r[2], p.tnear[k] = 0.0f;
    p.dir_x[k] = r[3], p.dir_y[k] = r[4], p.dir_z[k] = r[5], p.time[k] = 0.0f;
    p.tfar[k] = set.t_max, p.mask[k] = ~0u, p.id[k] = 0, p.flags[k] = 0;
  }
}

void closest_packets(RTCScene scene, const RaySet& set, RTCRayQueryFlags flags, int threads,
                     Answers& out) {
  in_chunks(set.count(), threads, [&](size_t begin, size_t end) {
    RTCIntersectArguments args;
    rtcInitIntersectArguments(&args);
    args.flags = flags;
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[kPacket];
    for (size_t first = begin; first < end; first += kPacket) {
      size_t n = std::min(kPacket, end - first);
      fill_packet(rh.ray, valid, set, first, n);
      for (size_t k = 0; k < kPacket; ++k) {
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene, &rh, &args);
      for (size_t k = 0; k < n; ++k)
        out[first + k] =
            rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? -1 : int32_t(rh.hit.primID[k]);
    }
  });
}

void anyhit_packets(RTCScene scene, const RaySet& set, RTCRayQueryFlags flags, int threads,
                    Answers& out) {
  in_chunks(set.count(), threads, [&](size_t begin, size_t end) {
    RTCOccludedArguments args;
    rtcInitOccludedArguments(&args);
    args.flags = flags;
    alignas(64) RTCRay16 ray;
    alignas(64) int valid[kPacket];
    for (size_t first = begin; first < end; first += kPacket) {
      size_t n = std::min(kPacket, end - first);
      fill_packet(ray, valid, set, first, n);
      rtcOccluded16(valid, scene, &ray, &args);
      for (size_t k = 0; k < n; ++k) out[first + k] = ray.tfar[k] == -INFINITY ? 1 : 0;
    }
  });
}

// W untimed runs, then R timed ones; the times in ms.
std::vector<double> timed(int warmup, int runs, const std::function<void()>& f) {
  for (int i = 0; i < warmup; ++i) f();
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    auto start = std::chrono::steady_clock::now();
    f();
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return ms;
}

std::string json_list(const std::vector<double>& xs) {
  std::string s = "[";
  char buffer[32];
  for (size_t i = 0; i < xs.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%s%.4f", i ? ", " : "", xs[i]);
    s += buffer;
  }
  return s + "]";
}

std::string library_version(RTCDevice device) {
  return std::to_string(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MAJOR)) + "." +
         std::to_string(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MINOR)) + "." +
         std::to_string(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_PATCH));
}

RTCDevice new_device(const std::string& config) {
  RTCDevice device = rtcNewDevice(config.c_str());
  if (!device) fail("rtcNewDevice(\"" + config + "\") failed");
  rtcSetDeviceErrorFunction(device, on_error, nullptr);
  return device;
}

void write_answers(const std::string& path, const Answers& answers, bool bytes) {
  std::ofstream out(path, std::ios::binary);
  if (bytes) {
    std::vector<uint8_t> b(answers.begin(), answers.end());
    out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
  } else {
    out.write(reinterpret_cast<const char*>(answers.data()),
              std::streamsize(answers.size() * sizeof(int32_t)));
  }
  if (!out) fail("cannot write " + path);
}

size_t differing(const Answers& a, const Answers& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir;
  std::vector<int> thread_counts{1, 2};
  int runs = 3, warmup = 1;
  bool hits = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) fail(a + " needs a value");
      return argv[++i];
    };
    if (a == "--version") {
      RTCDevice device = new_device("");
      std::printf("Embree library %s (RTC_DEVICE_PROPERTY_VERSION %zd), headers %s\n",
                  library_version(device).c_str(),
                  rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION), RTC_VERSION_STRING);
      rtcReleaseDevice(device);
      return 0;
    } else if (a == "--threads") {
      thread_counts.clear();
      std::string list = value();
      for (size_t at = 0; at <= list.size();) {
        size_t comma = std::min(list.find(',', at), list.size());
        thread_counts.push_back(std::atoi(list.substr(at, comma - at).c_str()));
        if (thread_counts.back() < 1) fail("--threads takes positive counts");
        at = comma + 1;
      }
    } else if (a == "--runs") {
      runs = std::atoi(value().c_str());
    } else if (a == "--warmup") {
      warmup = std::atoi(value().c_str());
    } else if (a == "--hits") {
      hits = true;
    } else if (dir.empty() && a[0] != '-') {
      dir = a;
    } else {
      fail("unknown argument " + a +
           " (usage: embree_bench DIR [--threads 1,2] [--runs R] [--warmup W] [--hits])");
    }
  }
  if (dir.empty()) fail("usage: embree_bench DIR [--threads 1,2] [--runs R] [--warmup W] [--hits]");
  if (runs < 1 || warmup < 0) fail("--runs must be at least 1 and --warmup at least 0");

  Mesh mesh = read_mesh(dir);
  std::vector<RaySet> sets;
  for (const char* name : kSets) sets.push_back(read_rays(dir, name));

  std::string records, counts, packets, version, properties;
  auto add = [](std::string& list, const std::string& item) {
    list += (list.empty() ? "" : ",\n  ") + item;
  };
  for (size_t t = 0; t < thread_counts.size(); ++t) {
    int threads = thread_counts[t];
    RTCDevice device = new_device("threads=" + std::to_string(threads));
    if (t == 0) {
      version = library_version(device);
      auto property = [&](RTCDeviceProperty p) {
        return std::to_string(rtcGetDeviceProperty(device, p));
      };
      properties = "{\"native_ray16\": " + property(RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) +
                   ", \"backface_culling\": " +
                   property(RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED) +
                   ", \"tasking_system\": " + property(RTC_DEVICE_PROPERTY_TASKING_SYSTEM) + "}";
    }
    for (auto [quality, what] : {std::pair{RTC_BUILD_QUALITY_MEDIUM, "build"},
                                 std::pair{RTC_BUILD_QUALITY_HIGH, "build-high"}}) {
      std::vector<double> ms;
      for (int i = 0; i < warmup + runs; ++i) {
        double build_ms;
        rtcReleaseScene(build_scene(device, mesh, quality, &build_ms));
        if (i >= warmup) ms.push_back(build_ms);
      }
      add(records, std::string("{\"what\": \"") + what + "\", \"threads\": " +
                       std::to_string(threads) + ", \"ms\": " + json_list(ms) + "}");
    }
    double ignored;
    RTCScene scene = build_scene(device, mesh, RTC_BUILD_QUALITY_MEDIUM, &ignored);
    for (const RaySet& set : sets) {
      RTCRayQueryFlags flags =
          set.name == "random" ? RTC_RAY_QUERY_FLAG_INCOHERENT : RTC_RAY_QUERY_FLAG_COHERENT;
      Answers single_closest(set.count()), packet_closest(set.count());
      Answers single_any(set.count()), packet_any(set.count());
      struct Mode {
        const char* what;
        const char* mode;
        void (*cast)(RTCScene, const RaySet&, RTCRayQueryFlags, int, Answers&);
        Answers* out;
      };
      const Mode modes[] = {{"closest", "single", closest_single, &single_closest},
                            {"closest", "packet16", closest_packets, &packet_closest},
                            {"anyhit", "single", anyhit_single, &single_any},
                            {"anyhit", "packet16", anyhit_packets, &packet_any}};
      for (const Mode& m : modes) {
        auto ms = timed(warmup, runs, [&] { m.cast(scene, set, flags, threads, *m.out); });
        add(records, std::string("{\"what\": \"") + m.what + "\", \"set\": \"" + set.name +
                         "\", \"mode\": \"" + m.mode + "\", \"threads\": " +
                         std::to_string(threads) + ", \"rays\": " + std::to_string(set.count()) +
                         ", \"ms\": " + json_list(ms) + "}");
      }
      if (t == 0) {
        auto hit = [](const Answers& a) {
          return std::to_string(std::count_if(a.begin(), a.end(), [](int32_t x) { return x >= 0; }));
        };
        auto occluded = [](const Answers& a) {
          return std::to_string(std::count(a.begin(), a.end(), 1));
        };
        add(counts, "\"" + set.name + "\": {\"closest\": " + hit(single_closest) +
                        ", \"anyhit\": " + occluded(single_any) + "}");
        add(packets, "\"" + set.name + "\": {\"closest\": " +
                         std::to_string(differing(single_closest, packet_closest)) +
                         ", \"anyhit\": " + std::to_string(differing(single_any, packet_any)) + "}");
        if (hits) {
          write_answers(dir + "/embree-" + set.name + ".closest", single_closest, false);
          write_answers(dir + "/embree-" + set.name + ".anyhit", single_any, true);
        }
      }
    }
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  std::printf(
      "{\"side\": \"embree\", \"version\": \"%s\", \"headers\": \"%s\", \"precision\": \"f32, not "
      "watertight\", \"properties\": %s, \"triangles\": %zu, \"hits\": {%s}, "
      "\"packet_vs_single_differ\": {%s}, \"warmup\": %d, \"records\": [\n  %s]}\n",
      version.c_str(), RTC_VERSION_STRING, properties.c_str(), mesh.triangles.size() / 3,
      counts.c_str(), packets.c_str(), warmup, records.c_str());
  return 0;
}

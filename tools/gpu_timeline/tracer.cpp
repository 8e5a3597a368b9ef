// A CUPTI activity tracer (tools/gpu_timeline/run.sh): loaded into a CUDA process through
// CUDA_INJECTION64_PATH, it records every kernel, copy, memset and runtime call with its start
// and end (GPU timestamps, ns) and writes them to TRACE_OUT (default /tmp/trace.csv) at exit,
// one per line: kind (K kernel, M copy, S memset, A runtime call), name, start, end, stream
// (thread for A), correlation id, grid x or bytes, block x. timeline.py prints a frame of it.
#include <cupti.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>
static std::mutex mu;
static std::vector<std::string> lines;
static void CUPTIAPI Req(uint8_t** buf, size_t* size, size_t* maxrec) {
  *size = 8 << 20;
  *buf = static_cast<uint8_t*>(aligned_alloc(8, *size));
  *maxrec = 0;
}
static void CUPTIAPI Done(CUcontext, uint32_t, uint8_t* buf, size_t, size_t valid) {
  CUpti_Activity* r = nullptr;
  char line[1024];
  std::lock_guard<std::mutex> l(mu);
  while (cuptiActivityGetNextRecord(buf, valid, &r) == CUPTI_SUCCESS) {
    switch (r->kind) {
      case CUPTI_ACTIVITY_KIND_CONCURRENT_KERNEL:
      case CUPTI_ACTIVITY_KIND_KERNEL: {
        auto* k = reinterpret_cast<CUpti_ActivityKernel10*>(r);
        std::string n = k->name ? k->name : "?";
        if (n.size() > 200) n = n.substr(0, 200);
        for (char& c : n) if (c == ',') c = ';';
        snprintf(line, sizeof line, "K,%s,%llu,%llu,%u,%u,%d,%d\n", n.c_str(), (unsigned long long)k->start,
                 (unsigned long long)k->end, k->streamId, k->correlationId, k->gridX, k->blockX);
        lines.emplace_back(line);
        break;
      }
      case CUPTI_ACTIVITY_KIND_MEMCPY: {
        auto* m = reinterpret_cast<CUpti_ActivityMemcpy6*>(r);
        snprintf(line, sizeof line, "M,copy%d,%llu,%llu,%u,%u,%llu,0\n", int(m->copyKind), (unsigned long long)m->start,
                 (unsigned long long)m->end, m->streamId, m->correlationId, (unsigned long long)m->bytes);
        lines.emplace_back(line);
        break;
      }
      case CUPTI_ACTIVITY_KIND_MEMSET: {
        auto* m = reinterpret_cast<CUpti_ActivityMemset4*>(r);
        snprintf(line, sizeof line, "S,memset,%llu,%llu,%u,%u,%llu,0\n", (unsigned long long)m->start,
                 (unsigned long long)m->end, m->streamId, m->correlationId, (unsigned long long)m->bytes);
        lines.emplace_back(line);
        break;
      }
      case CUPTI_ACTIVITY_KIND_RUNTIME: {
        auto* a = reinterpret_cast<CUpti_ActivityAPI*>(r);
        const char* n = nullptr;
        cuptiGetCallbackName(CUPTI_CB_DOMAIN_RUNTIME_API, a->cbid, &n);
        snprintf(line, sizeof line, "A,%s,%llu,%llu,%u,%u,0,0\n", n ? n : "?", (unsigned long long)a->start,
                 (unsigned long long)a->end, a->threadId, a->correlationId);
        lines.emplace_back(line);
        break;
      }
      default: break;
    }
  }
  free(buf);
}
static void AtExit() {
  cuptiActivityFlushAll(1);
  const char* p = getenv("TRACE_OUT");
  FILE* f = fopen(p ? p : "/tmp/trace.csv", "w");
  std::lock_guard<std::mutex> l(mu);
  for (auto& s : lines) fputs(s.c_str(), f);
  fclose(f);
}
extern "C" int InitializeInjection(void) {
  cuptiActivityRegisterCallbacks(Req, Done);
  cuptiActivityEnable(CUPTI_ACTIVITY_KIND_CONCURRENT_KERNEL);
  cuptiActivityEnable(CUPTI_ACTIVITY_KIND_MEMCPY);
  cuptiActivityEnable(CUPTI_ACTIVITY_KIND_MEMSET);
  cuptiActivityEnable(CUPTI_ACTIVITY_KIND_RUNTIME);
  atexit(AtExit);
  return 1;
}

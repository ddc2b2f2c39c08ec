// meshsal (internal): the phases of run_request, one file each: the meshes read
// (request_input.cpp), S and the views' score (request_saliency.cpp), simplification and
// levels of detail (request_simplify.cpp), the view, picture, map and page
// (request_views.cpp). They share one RequestRun.
#pragma once
#include <string>
#include <vector>

#include "core/timer.h"
#include "meshsal/meshsal.h"

namespace meshsal {

class ReadObserver;  // io/read_observer.h

struct RequestRun {
  RequestRun(const Request& r, RequestResult& out) : request(r), result(out), saliency(r.saliency) {}
  const Request& request;
  RequestResult& result;
  // What S is computed with: the request's options, with the device a warm-up resolved.
  SaliencyOptions saliency;
  // The input read plainly (S, the saliency PLY, the views) and with its attributes (the
  // outputs that carry them); either points at the caller's mesh or at its copy here.
  const Mesh* plain = nullptr;
  const Mesh* attributed = nullptr;
  Mesh plain_read, attributed_read;
  LoadReport plain_report;  // the plain read's (what it left unread)
  // S of each mesh once it is had (read back or computed), and Sm with it where computed.
  bool has_plain_s = false, has_attributed_s = false;
  SaliencyResult plain_s;
  std::vector<double> attributed_s;
  std::string attributed_s_device;
  // The input file holds S (a PLY's quality, a glTF's _SALIENCY: seen when it was read
  // plainly); the file S is read back from ("" = computed), once it is known.
  bool input_has_saliency = false;
  bool saliency_file_known = false;
  std::string saliency_file;
  // What the run waited for the device's warm-up after reading (warm_up_saliency), -1 when
  // there was none: the first computed S shows it as its first stage ("device warm-up").
  double warm_up_wait = -1;
  // Told what the first read has read while it reads (read_upload.h); null for none.
  ReadObserver* read_observer = nullptr;
  Timer timer;  // since the run began
  double timer_seconds() const;
};

// Which meshes the request's outputs read (the rule every command has had): a saliency PLY
// and the views the plain mesh, every other mesh output the mesh with its attributes.
bool needs_plain_mesh(const Request& r);
bool needs_attributed_mesh(const Request& r);

// Reads what the outputs need (unless the caller gave it).
void read_input(RequestRun& run);

// S on the plain mesh (computed, or read back), into run.plain_s; `smoothed`: with Sm.
void plain_saliency(RequestRun& run, bool smoothed);
// S on the mesh with attributes: the plain mesh's when the two have the same vertices,
// else read back or computed on it.
const std::vector<double>& attributed_saliency(RequestRun& run);

// The saliency output (in memory: the plain or attributed mesh by its format).
void write_saliency_output(RequestRun& run);
// The score the views show (S or |H|) on the plain mesh, into result.score.
void view_score(RequestRun& run);

void make_simplified(RequestRun& run);
void make_lod(RequestRun& run);
void make_views(RequestRun& run);

// A mesh written by the request: write_mesh with S (or none), its side files checked
// first, the file and side files added to result.outputs, and mesh_output_note's note
// added to result.notes.
void write_request_mesh(RequestRun& run, const std::string& path, const Mesh& mesh,
                        const std::vector<double>& saliency = {});

// The side files of a mesh output (mesh_side_files), checked as its main file was.
std::vector<std::string> check_side_files(RequestRun& run, const std::string& path, const Mesh& mesh);

// Adds `note` to result.notes once, and tells request.saliency.notice.
void add_note(RequestRun& run, const std::string& note);

// Whether this process writes the run's files: under an exchange (the saliency's or the
// simplification's: MPI ranks) the processes compute together and rank 0 alone writes.
bool writes_files(const Request& r);

// The file name of a path ("models/bunny.ply" -> "bunny.ply").
std::string file_name_of(const std::string& path);

}  // namespace meshsal

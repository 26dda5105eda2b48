// VTK frames in pieces (io/vtk_writer.h, output.vtk_pieces): two Worlds that share four floes, each owning two and
// holding the others as ghosts, write a piece each; the frame's .pvtp, read by VTK's parallel reader, holds every
// floe once with the values of the single file one World writes; a missing piece is refused, and a restart removes
// every piece of the frames after it.
#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "text_file.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/world.h"
#include "formats/atomic_file.h"
#include "io/vtk_writer.h"

namespace fs = std::filesystem;
using namespace polyfloe;

namespace {

constexpr double kWater = 1025.0;  // [kg/m^3]

// Four squares in a row, each pressing on the next (three contacts), ids 40, 10, 30, 20 from left to right.
std::unique_ptr<dynamics::World> make_world() {
  auto world = std::make_unique<dynamics::World>(dynamics::WorldSettings{});
  auto square = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::regular(4, 3.0));
  const dynamics::BodyId ids[4] = {40, 10, 30, 20};
  for (int k = 0; k < 4; ++k) {
    dynamics::BodyDesc d;
    d.shape = square;
    d.density = 920.0;
    d.id = ids[k];
    d.position = {4.2 * k, 0.1 * k};
    d.yaw = 0.7853981633974483 + 0.01 * k;
    d.velocity = {0.1 * k, -0.05};
    d.angular_velocity = 0.02 * k;
    world->add_body(d);
  }
  world->compute_forces(1e-3);
  return world;
}

// Each cell of a frame by its points and values (cells: the id array's value; points of contacts: by position).
using Content = std::map<std::string, std::vector<double>>;

Content content(vtkPolyData* pd) {
  Content out;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c) {
    std::vector<double> v;
    vtkIdList* ids = pd->GetCell(c)->GetPointIds();
    for (vtkIdType j = 0; j < ids->GetNumberOfIds(); ++j) {
      double p[3];
      pd->GetPoint(ids->GetId(j), p);
      v.insert(v.end(), p, p + 3);
      for (int a = 0; a < pd->GetPointData()->GetNumberOfArrays(); ++a)
        for (int k = 0; k < pd->GetPointData()->GetArray(a)->GetNumberOfComponents(); ++k)
          v.push_back(pd->GetPointData()->GetArray(a)->GetComponent(ids->GetId(j), k));
    }
    for (int a = 0; a < pd->GetCellData()->GetNumberOfArrays(); ++a)
      for (int k = 0; k < pd->GetCellData()->GetArray(a)->GetNumberOfComponents(); ++k)
        v.push_back(pd->GetCellData()->GetArray(a)->GetComponent(c, k));
    std::string key(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
    EXPECT_TRUE(out.emplace(key, v).second) << "a cell twice";
  }
  return out;
}

template <class Reader>
vtkSmartPointer<vtkPolyData> read(const fs::path& file) {
  vtkNew<Reader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0u) << file;
  return reader->GetOutput();
}

}  // namespace

TEST(VtkPieces, TwoRanksPiecesHoldEveryFloeOnceAsTheSingleFile) {
  tsupport::TestDir scratch;
  const fs::path whole_dir = scratch.path() / "whole", dir = scratch.path() / "pieces";
  const auto whole = make_world();
  io::VtkSeriesWriter(whole_dir, false, kWater).write_frame(*whole);

  // Rank 0 owns the two left floes, rank 1 the two right ones; each holds the others as ghosts. (Contacts: each
  // rank's are those it evaluated, which takes the step's exchange: the distributed runs check them.)
  auto left = make_world(), right = make_world();
  for (int i = 0; i < 4; ++i) {
    left->set_ghost(i, left->positions()[static_cast<std::size_t>(i)].x() > 6.0);
    right->set_ghost(i, right->positions()[static_cast<std::size_t>(i)].x() < 6.0);
  }
  io::VtkSeriesWriter writer(dir, false, kWater, nullptr, 2);
  EXPECT_EQ(writer.pieces(), 2);
  writer.begin_pieces(false);
  io::write_vtk_piece(dir, *left, 0, 0, false, kWater);
  io::write_vtk_piece(dir, *right, 0, 1, false, kWater);
  writer.write_frame(*whole);

  const std::string pvd = tsupport::slurp(dir / "floes.pvd");
  EXPECT_NE(pvd.find("file=\"floes/floes_000000.pvtp\""), std::string::npos) << pvd;
  EXPECT_EQ(read<vtkXMLPolyDataReader>(dir / "floes" / "floes_000000_0.vtp")->GetNumberOfCells(),
            2 * (4 + 2));  // two squares: top, bottom, four sides each
  const Content one = content(read<vtkXMLPolyDataReader>(whole_dir / "floes" / "floes_000000.vtp"));
  const Content both = content(read<vtkXMLPPolyDataReader>(dir / "floes" / "floes_000000.pvtp"));
  EXPECT_EQ(one.size(), 4u * 6u);
  EXPECT_EQ(both.size(), one.size());
  EXPECT_TRUE(both == one) << "the pieces together differ from the single file";
}

TEST(VtkPieces, AFrameWhosePieceIsMissingIsRefusedNamingIt) {
  tsupport::TestDir dir;
  const auto world = make_world();
  io::VtkSeriesWriter writer(dir.path(), false, kWater, nullptr, 2);
  writer.begin_pieces(false);
  io::write_vtk_piece(dir.path(), *world, 0, 0, false, kWater);
  try {
    writer.write_frame(*world);
    FAIL() << "a frame with a missing piece was written";
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("floes_000000_1.vtp is missing"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.path() / "floes" / "floes_000000.pvtp"));
  EXPECT_FALSE(fs::exists(dir.path() / "floes.pvd"));  // no collection lists an incomplete frame
}

TEST(VtkPieces, ARestartKeepsTheFramesBeforeItAndRemovesEveryPieceOfTheLaterOnes) {
  tsupport::TestDir dir;
  const auto world = make_world();
  {
    io::VtkSeriesWriter writer(dir.path(), true, kWater, nullptr, 3);
    for (int frame = 0; frame < 3; ++frame) {
      writer.begin_pieces(false);
      for (int k = 0; k < 3; ++k) io::write_vtk_piece(dir.path(), *world, frame, k, true, kWater);
      writer.write_frame(*world);
    }
  }
  io::VtkSeriesWriter again(dir.path(), true, kWater, nullptr, 2);
  const std::vector<double> times{0.0, 0.0};
  again.resume(times, false);
  EXPECT_EQ(again.frames(), 2);
  for (const char* series : {"floes", "contacts"}) {
    const fs::path d = dir.path() / series;
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(fs::exists(d / (std::string(series) + "_000001_" + std::to_string(k) + ".vtp"))) << series << k;
      EXPECT_FALSE(fs::exists(d / (std::string(series) + "_000002_" + std::to_string(k) + ".vtp"))) << series << k;
    }
    EXPECT_TRUE(fs::exists(d / (std::string(series) + "_000001.pvtp")));
    EXPECT_FALSE(fs::exists(d / (std::string(series) + "_000002.pvtp")));
  }
  const std::string pvd = tsupport::slurp(dir.path() / "floes.pvd");
  EXPECT_NE(pvd.find("floes/floes_000001.pvtp"), std::string::npos) << pvd;
  EXPECT_EQ(pvd.find("floes_000002"), std::string::npos) << pvd;
}

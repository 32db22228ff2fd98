#include "coupling/cfd_dem/drag_models.hpp"

namespace amphora::coupling::cfd_dem {

std::optional<DragModel> drag_model_from_name(const std::string& name) {
  if (name == "di_felice") return DragModel::di_felice;
  if (name == "rong") return DragModel::rong;
  if (name == "beetstra") return DragModel::beetstra;
  if (name == "gidaspow") return DragModel::gidaspow;
  return std::nullopt;
}

const char* drag_model_names() { return "di_felice, rong, beetstra, gidaspow"; }

}  // namespace amphora::coupling::cfd_dem

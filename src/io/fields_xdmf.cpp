// XDMF 2 sidecar for fields.h5: ParaView (Xdmf reader) opens fields.xmf directly.
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "adrsph/io/fields_h5.hpp"

namespace adrsph {
namespace {

void data_item(std::ostream& os, std::size_t n, const char* type, int precision,
               const std::string& h5, const std::string& frame, const char* name) {
  os << "          <DataItem Dimensions=\"" << n << "\" NumberType=\"" << type << "\" Precision=\""
     << precision << "\" Format=\"HDF\">" << h5 << ":/" << frame << "/" << name << "</DataItem>\n";
}

}  // namespace

void write_fields_xdmf(const std::filesystem::path& xmf, const std::string& h5_name,
                       const std::vector<FieldFrameInfo>& frames,
                       const std::vector<std::string>& more_c) {
  std::vector<std::string> attributes = {"vx", "vy", "rho", "p", "c"};
  attributes.insert(attributes.end(), more_c.begin(), more_c.end());
  attributes.push_back("kind");
  std::ostringstream os;
  os.precision(17);
  os << "<?xml version=\"1.0\" ?>\n"
     << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
     << "<Xdmf Version=\"2.0\">\n"
     << "  <Domain>\n"
     << "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    const std::string frame = field_frame_name(i);
    os << "      <Grid Name=\"" << frame << "\" GridType=\"Uniform\">\n"
       << "        <Time Value=\"" << f.t << "\" />\n"
       << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << f.n
       << "\" NodesPerElement=\"1\" />\n"
       << "        <Geometry GeometryType=\"X_Y\">\n";
    data_item(os, f.n, "Float", 8, h5_name, frame, "x");
    data_item(os, f.n, "Float", 8, h5_name, frame, "y");
    os << "        </Geometry>\n";
    for (const std::string& attribute : attributes) {
      const char* name = attribute.c_str();
      const bool is_kind = attribute == "kind";
      os << "        <Attribute Name=\"" << name
         << "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
      data_item(os, f.n, is_kind ? "UChar" : "Float", is_kind ? 1 : 8, h5_name, frame, name);
      os << "        </Attribute>\n";
    }
    os << "      </Grid>\n";
  }
  os << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  std::ofstream out(xmf, std::ios::binary | std::ios::trunc);
  out << os.str();
  out.close();
  if (!out) throw std::runtime_error(xmf.string() + ": cannot write the XDMF file");
}

}  // namespace adrsph

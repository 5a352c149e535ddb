// The study's YAML body file (issue 5) and its error messages.

#include "study_fixtures.hpp"

namespace rocking_monitor::core::study {
namespace {

// ------------------------------------------------------------------ YAML bodies

fs::path write_yaml(const std::string& tag, const std::string& text) {
  const fs::path p = temp_dir("yaml_" + tag) / "bodies.yaml";
  std::ofstream(p) << text;
  return p;
}

TEST(StudyBodiesYaml, ReadsBodiesAndExpandsEccentricityLists) {
  const fs::path p = write_yaml("ok",
                                "bodies:\n"
                                "  - name: cabinet\n"
                                "    width: 0.6\n"
                                "    cg_height: 0.9\n"
                                "    nu1: [0.5, 0.3]\n"
                                "  - width: 0.2\n"
                                "    cg_height: 0.5\n"
                                "    radius_of_gyration: 0.3\n"
                                "    restitution: 0.9\n"
                                "    mu_s: 0.6\n");
  const auto b = load_bodies_yaml(p.string());
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].name, "cabinet_nu0.5");
  EXPECT_EQ(b[1].name, "cabinet_nu0.3");
  EXPECT_DOUBLE_EQ(b[1].parameters.nu1, 0.3);
  EXPECT_DOUBLE_EQ(b[0].parameters.radius_of_gyration, b[1].parameters.radius_of_gyration);
  EXPECT_DOUBLE_EQ(b[0].parameters.radius_of_gyration, Body::homogeneous_radius_of_gyration(0.6, 0.9));
  EXPECT_EQ(b[2].name, "body1");
  EXPECT_DOUBLE_EQ(b[2].parameters.radius_of_gyration, 0.3);
  EXPECT_DOUBLE_EQ(b[2].parameters.restitution, 0.9);
  EXPECT_DOUBLE_EQ(b[2].parameters.mu_s, 0.6);
  EXPECT_DOUBLE_EQ(b[2].parameters.nu1, 0.5);
}

TEST(StudyBodiesYaml, ErrorsNameTheFileItemAndField) {
  struct Bad {
    const char* text;
    std::vector<std::string> expect;  // substrings of the message
  };
  const std::vector<Bad> cases{
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1}\n  - {name: vase, width: -1, cg_height: 1}\n",
       {"bodies[1] (vase)", "width", "-1"}},
      {"bodies:\n  - {name: a, width: 0.5}\n", {"bodies[0] (a)", "cg_height", "missing"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1, hieght: 2}\n", {"bodies[0] (a)", "hieght", "unknown field"}},
      {"bodies:\n  - {name: a, width: wide, cg_height: 1}\n", {"bodies[0] (a)", "width", "'wide'"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1, nu1: [0.5, 1.5]}\n", {"bodies[0] (a)", "nu1", "1.5"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1}\n  - {name: a, width: 0.4, cg_height: 1}\n",
       {"bodies[1] (a)", "used twice"}},
      {"bodies:\n  - name: a\n   width: [\n", {"bodies.yaml:"}},
      {"things: []\n", {"unknown top-level key 'things'"}},
      {"items: []\n", {"non-empty list"}},
      {"bodies: []\n", {"non-empty list"}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path p = write_yaml("bad" + std::to_string(i), cases[i].text);
    try {
      load_bodies_yaml(p.string());
      ADD_FAILURE() << "no error for: " << cases[i].text;
    } catch (const StudyError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
      for (const auto& s : cases[i].expect) EXPECT_NE(msg.find(s), std::string::npos) << msg << " lacks " << s;
    }
  }
  EXPECT_THROW(load_bodies_yaml("/nonexistent/bodies.yaml"), StudyError);
}

}  // namespace
}  // namespace rocking_monitor::core::study

// The viewer's keys: names, scripts, and what each press changes.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>

#include "viewer/keys.h"

namespace rtm::viewer {
namespace {

TEST(Keys, NamesAndScripts) {
    EXPECT_EQ(key_code("w"), GLFW_KEY_W);
    EXPECT_EQ(key_code("W"), GLFW_KEY_W);
    EXPECT_EQ(key_code("2"), GLFW_KEY_2);
    EXPECT_EQ(key_code("Space"), GLFW_KEY_SPACE);
    EXPECT_EQ(key_code("F12"), GLFW_KEY_F12);
    EXPECT_EQ(key_code("F13"), -1);
    EXPECT_EQ(key_code("?"), -1);
    EXPECT_EQ(parse_key_script("2,G,i"), (std::vector<int>{GLFW_KEY_2, GLFW_KEY_G, GLFW_KEY_I}));
    EXPECT_TRUE(parse_key_script("").empty());
    try {
        parse_key_script("2,nope");
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("\"nope\""), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_key_script("2,"), std::invalid_argument);
}

TEST(Keys, MethodAndToggles) {
    ViewSettings s;
    KeyRequests r;
    EXPECT_TRUE(apply_key(GLFW_KEY_1, s, r));
    EXPECT_EQ(s.method, RenderMethod::flat);
    EXPECT_TRUE(apply_key(GLFW_KEY_5, s, r));
    EXPECT_EQ(s.method, RenderMethod::raycast);
    const ViewSettings before = s;
    for (int k : {GLFW_KEY_G, GLFW_KEY_Z, GLFW_KEY_K, GLFW_KEY_B, GLFW_KEY_H, GLFW_KEY_I, GLFW_KEY_O, GLFW_KEY_V})
        apply_key(k, s, r);
    EXPECT_NE(s.side_polygons, before.side_polygons);
    EXPECT_NE(s.depth_correction, before.depth_correction);
    EXPECT_NE(s.skips, before.skips);
    EXPECT_NE(s.coverage, before.coverage);
    EXPECT_NE(s.panel, before.panel);
    EXPECT_NE(s.insets, before.insets);
    EXPECT_NE(s.outlines, before.outlines);
    EXPECT_NE(s.vsync, before.vsync);
    // L cycles auto, 0, 1, 2, 3, auto.
    s.level = -1;
    for (int want : {0, 1, 2, 3, -1}) {
        apply_key(GLFW_KEY_L, s, r);
        EXPECT_EQ(s.level, want);
    }
    // X cycles the split view.
    apply_key(GLFW_KEY_X, s, r);
    EXPECT_EQ(s.split, SplitMode::method);
    apply_key(GLFW_KEY_X, s, r);
    EXPECT_EQ(s.split, SplitMode::truth);
    apply_key(GLFW_KEY_X, s, r);
    EXPECT_EQ(s.split, SplitMode::off);
    EXPECT_FALSE(apply_key(GLFW_KEY_TAB, s, r));
}

TEST(Keys, MovementKeysFlyOnlyWithTheFlyCamera) {
    ViewSettings s;
    KeyRequests r;
    EXPECT_FALSE(apply_key(GLFW_KEY_W, s, r));  // orbit: W does nothing
    EXPECT_TRUE(apply_key(GLFW_KEY_Q, s, r));   // orbit: Q quits
    EXPECT_TRUE(r.quit);
    r = {};
    apply_key(GLFW_KEY_C, s, r);
    ASSERT_TRUE(s.fly);
    apply_key(GLFW_KEY_W, s, r);
    apply_key(GLFW_KEY_W, s, r);
    apply_key(GLFW_KEY_D, s, r);
    apply_key(GLFW_KEY_Q, s, r);  // fly: Q goes down
    EXPECT_FALSE(r.quit);
    EXPECT_EQ(r.fly, glm::dvec3(1, -1, 2));
    apply_key(GLFW_KEY_F, s, r);
    apply_key(GLFW_KEY_P, s, r);
    apply_key(GLFW_KEY_SPACE, s, r);
    EXPECT_TRUE(r.frame && r.screenshot && r.toggle_play);
}

TEST(Split, ParsesMethodsAndTruth) {
    ViewSettings s;
    parse_split("truth", s);
    EXPECT_EQ(s.split, SplitMode::truth);
    parse_split("flat", s);
    EXPECT_EQ(s.split, SplitMode::method);
    EXPECT_EQ(s.split_method, RenderMethod::flat);
    EXPECT_THROW(parse_split("raycast", s), std::invalid_argument);
    EXPECT_THROW(parse_split("nope", s), std::invalid_argument);
}

}  // namespace
}  // namespace rtm::viewer

// The effect runtime on the device: values reaching the GPU, passes drawing,
// stream output, tessellation, compute, FX11 state persistence.
#include <cmath>

#include "effect_test_util.h"
#include "renderer/particle_rule.h"

namespace effects_test {
namespace {

using rhi::ComPtr;

// Defaults and Set* values reach the GPU through layouts where glslang and fxc
// pack differently ($Globals vectors after a scalar, scalars after an array,
// float3x3, row_major): a compute pass copies every component out.
TEST_F(EffectTest, DefaultsAndSetValuesReachTheGpu) {
  auto effect = FromMemory(R"(
float g_a = 1;
float2 g_b = float2(2, 3);          // fxc: offset 4; glslang's $Global: 8
cbuffer Params {
  float arr[2] = {4, 5};
  float after = 6;                  // fxc: packed after arr[1] (20); glslang: 32
  float3x3 m = {7, 8, 9, 10, 11, 12, 13, 14, 15};
  row_major float2x3 r = {16, 17, 18, 19, 20, 21};
  int i = -22;
};
RWStructuredBuffer<float> Out;
[numthreads(1, 1, 1)] void CS() {
  Out[0] = g_a; Out[1] = g_b.x; Out[2] = g_b.y; Out[3] = arr[0]; Out[4] = arr[1]; Out[5] = after;
  for (int k = 0; k < 9; ++k) Out[6 + k] = m[k / 3][k % 3];
  for (int j = 0; j < 6; ++j) Out[15 + j] = r[j / 3][j % 3];
  Out[21] = i;
}
technique11 T { pass P { SetComputeShader(CompileShader(cs_5_0, CS())); } }
)");
  ASSERT_TRUE(effect);
  Rw out = MakeRw(22);
  ASSERT_EQ(effect->GetVariableByName("Out")->AsUnorderedAccessView()->SetUnorderedAccessView(out.uav.Get()),
            rhi::S_OK);
  fx::EffectPass* pass = effect->GetTechniqueByIndex(0)->GetPassByIndex(0);
  ASSERT_EQ(pass->Apply(0, context.Get()), rhi::S_OK);
  context->Dispatch(1, 1, 1);
  std::vector<float> got = ReadBufferAs<float>(out.buffer.Get());
  for (int k = 0; k < 21; ++k) EXPECT_EQ(got[k], float(k + 1)) << "component " << k;
  EXPECT_EQ(got[21], -22.0f);

  // Set*: FX11 semantics (SetMatrix takes a row-major 4x4 whatever the packing).
  effect->GetVariableByName("g_a")->AsScalar()->SetFloat(101);
  const float b[4] = {102, 103, 0, 0};
  effect->GetVariableByName("g_b")->AsVector()->SetFloatVector(b);
  const float arr[2] = {104, 105};
  effect->GetVariableByName("arr")->AsScalar()->SetFloatArray(arr, 0, 2);
  effect->GetVariableByName("after")->AsScalar()->SetFloat(106);
  float m[16] = {}, r[16] = {};
  for (int k = 0; k < 9; ++k) m[(k / 3) * 4 + k % 3] = 107.0f + k;
  for (int j = 0; j < 6; ++j) r[(j / 3) * 4 + j % 3] = 116.0f + j;
  effect->GetVariableByName("m")->AsMatrix()->SetMatrix(m);
  effect->GetVariableByName("r")->AsMatrix()->SetMatrix(r);
  effect->GetVariableByName("i")->AsScalar()->SetInt(-122);
  float back[16];
  effect->GetVariableByName("m")->AsMatrix()->GetMatrix(back);
  EXPECT_EQ(back[1 * 4 + 2], 112.0f);
  ASSERT_EQ(pass->Apply(0, context.Get()), rhi::S_OK);
  context->Dispatch(1, 1, 1);
  got = ReadBufferAs<float>(out.buffer.Get());
  for (int k = 0; k < 21; ++k) EXPECT_EQ(got[k], float(k + 101)) << "component " << k;
  EXPECT_EQ(got[21], -122.0f);

  // SetMatrixTranspose takes the transpose.
  float t[16] = {};
  for (int k = 0; k < 9; ++k) t[(k % 3) * 4 + k / 3] = 200.0f + k;
  effect->GetVariableByName("m")->AsMatrix()->SetMatrixTranspose(t);
  pass->Apply(0, context.Get());
  context->Dispatch(1, 1, 1);
  got = ReadBufferAs<float>(out.buffer.Get());
  for (int k = 0; k < 9; ++k) EXPECT_EQ(got[6 + k], 200.0f + k);
}

// Two CompileShader of one function with different uniform arguments differ.
TEST_F(EffectTest, UniformParameterVariantsAndComputeTechnique) {
  auto effect = Load(kShaderDir + "/tessellation.fx");
  ASSERT_TRUE(effect);
  Rw out = MakeRw(64);
  effect->GetVariableByName("Output")->AsUnorderedAccessView()->SetUnorderedAccessView(out.uav.Get());
  fx::EffectTechnique* fill = effect->GetTechniqueByName("Fill");
  ASSERT_EQ(fill->GetPassByName("Plus0")->Apply(0, context.Get()), rhi::S_OK);
  context->Dispatch(1, 1, 1);
  std::vector<uint32_t> plain = ReadBufferAs<uint32_t>(out.buffer.Get());
  effect->GetVariableByName("Scale")->AsScalar()->SetInt(5);
  ASSERT_EQ(fill->GetPassByName("Plus1000")->Apply(0, context.Get()), rhi::S_OK);
  context->Dispatch(1, 1, 1);
  std::vector<uint32_t> offset = ReadBufferAs<uint32_t>(out.buffer.Get());
  for (uint32_t i = 0; i < 64; ++i) {
    EXPECT_EQ(plain[i], i * 3);
    EXPECT_EQ(offset[i], i * 5 + 1000);
  }
}

// The hull/domain path draws exactly the triangle's pixels: the lower-left
// half of a 16x16 target (pixel centres never lie on its diagonal).
TEST_F(EffectTest, TessellatedTriangleCoversExactlyItsPixels) {
  auto effect = Load(kShaderDir + "/tessellation.fx");
  ASSERT_TRUE(effect);
  const float vertices[] = {-1, -1, 0, -1, 1, 0, 1, -1, 0};
  auto vb = MakeBuffer(rhi::BIND_VERTEX_BUFFER, vertices, sizeof vertices);
  fx::PASS_DESC pd;
  fx::EffectPass* pass = effect->GetTechniqueByName("Tessellate")->GetPassByIndex(0);
  pass->GetDesc(&pd);
  const rhi::INPUT_ELEMENT_DESC element{"POSITION", 0, rhi::DXGI_FORMAT_R32G32B32_FLOAT, 0, 0,
                                        rhi::INPUT_PER_VERTEX_DATA, 0};
  ComPtr<rhi::InputLayout> layout;
  ASSERT_EQ(device->CreateInputLayout(&element, 1, pd.pIAInputSignature, pd.IAInputSignatureSize,
                                      layout.GetAddressOf()),
            rhi::S_OK);
  rhi::RASTERIZER_DESC rs{};
  rs.FillMode = rhi::FILL_SOLID;
  rs.CullMode = rhi::CULL_NONE;
  rs.DepthClipEnable = TRUE;
  ComPtr<rhi::RasterizerState> noCull;
  device->CreateRasterizerState(&rs, noCull.GetAddressOf());
  Target target = MakeRenderTarget(16, 16);
  const float black[4] = {0, 0, 0, 0};
  context->ClearRenderTargetView(target.rtv.Get(), black);
  rhi::RenderTargetView* rtv = target.rtv.Get();
  context->OMSetRenderTargets(1, &rtv, nullptr);
  SetViewport(16, 16);
  context->RSSetState(noCull.Get());
  UINT stride = 12, offset = 0;
  rhi::Buffer* vbp = vb.Get();
  context->IASetInputLayout(layout.Get());
  context->IASetVertexBuffers(0, 1, &vbp, &stride, &offset);
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_3_CONTROL_POINT_PATCHLIST);
  ASSERT_EQ(pass->Apply(0, context.Get()), rhi::S_OK);
  context->Draw(3, 0);
  std::vector<uint8_t> pixels = ReadTexture(target.texture.Get());
  int wrong = 0;
  for (UINT y = 0; y < 16; ++y)
    for (UINT x = 0; x < 16; ++x) {
      uint32_t expected = y > x ? 0xFF00FF00u : 0u;  // ABGR of (0, 1, 0, 1)
      if (Pixel(pixels, 16, x, y) != expected) ++wrong;
    }
  EXPECT_EQ(wrong, 0);
}

// FX11: state a pass does not assign keeps what an earlier pass set.
TEST_F(EffectTest, StateSetByAnEarlierPassPersists) {
  auto effect = FromMemory(R"(
BlendState Additive { BlendEnable[0] = TRUE; SrcBlend[0] = ONE; DestBlend[0] = ONE; };
float4 VS(uint id : SV_VertexID) : SV_Position {
  return float4(float2((id << 1) & 2, id & 2) * float2(2, -2) + float2(-1, 1), 0, 1);
}
float4 PS(uniform float red) : SV_Target { return float4(red, 0, 0, 1); }
technique11 T {
  pass SetsBlend { SetVertexShader(CompileShader(vs_5_0, VS())); SetPixelShader(CompileShader(ps_5_0, PS(0.25)));
                   SetBlendState(Additive, float4(0, 0, 0, 0), 0xFFFFFFFF); }
  pass KeepsBlend { SetPixelShader(CompileShader(ps_5_0, PS(0.5))); }
}
)");
  ASSERT_TRUE(effect);
  Target target = MakeRenderTarget(4, 4);
  const float clear[4] = {0.25f, 0, 0, 1};
  context->ClearRenderTargetView(target.rtv.Get(), clear);
  rhi::RenderTargetView* rtv = target.rtv.Get();
  context->OMSetRenderTargets(1, &rtv, nullptr);
  SetViewport(4, 4);
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  fx::EffectTechnique* t = effect->GetTechniqueByIndex(0);
  ASSERT_EQ(t->GetPassByIndex(0)->Apply(0, context.Get()), rhi::S_OK);
  ASSERT_EQ(t->GetPassByIndex(1)->Apply(0, context.Get()), rhi::S_OK);
  context->Draw(3, 0);  // the vertex shader and the additive blend of pass 0, the PS of pass 1
  std::vector<uint8_t> pixels = ReadTexture(target.texture.Get());
  EXPECT_NEAR(int(Pixel(pixels, 4, 1, 1) & 0xFF), 191, 1);  // 0.25 + 0.5 (without the blend: 128)
}

// document 000 through the effect: the update technique streams out exactly
// the CPU model's particle count after every update (DrawAuto after the first),
// and the draw technique renders them.
TEST_F(EffectTest, ParticlesMatchTheCpuModel) {
  auto effect = Load(kShaderDir + "/particles.fx");
  ASSERT_TRUE(effect);
  renderer::ParticleRule rule{20, 3, 4, 6};
  effect->GetVariableByName("SpawnPerFrame")->AsScalar()->SetInt(rule.spawnPerFrame);
  effect->GetVariableByName("MinLife")->AsScalar()->SetInt(rule.minLife);
  effect->GetVariableByName("LifeRange")->AsScalar()->SetInt(rule.lifeRange);
  struct Particle {
    float origin[3], velocity[3];
    uint32_t seedAge[2], kindLife[2];
  };
  std::vector<Particle> emitters(rule.emitters);
  for (uint32_t e = 0; e < rule.emitters; ++e) emitters[e] = {{0.1f * e, 0, 0}, {0, 0, 0}, {e, 0}, {0, 0}};
  const UINT capacity = rule.emitters * (1 + rule.spawnPerFrame * (rule.minLife + rule.lifeRange));
  auto init = MakeBuffer(rhi::BIND_VERTEX_BUFFER, emitters.data(), UINT(emitters.size() * sizeof(Particle)));
  ComPtr<rhi::Buffer> buffers[2];
  for (auto& b : buffers)
    b = MakeBuffer(rhi::BIND_VERTEX_BUFFER | rhi::BIND_STREAM_OUTPUT, nullptr, capacity * UINT(sizeof(Particle)));
  fx::EffectPass* update = effect->GetTechniqueByName("Update")->GetPassByIndex(0);
  fx::PASS_DESC pd;
  update->GetDesc(&pd);
  const rhi::INPUT_ELEMENT_DESC elements[] = {
      {"ORIGIN", 0, rhi::DXGI_FORMAT_R32G32B32_FLOAT, 0, 0, rhi::INPUT_PER_VERTEX_DATA, 0},
      {"VELOCITY", 0, rhi::DXGI_FORMAT_R32G32B32_FLOAT, 0, 12, rhi::INPUT_PER_VERTEX_DATA, 0},
      {"SEEDAGE", 0, rhi::DXGI_FORMAT_R32G32_UINT, 0, 24, rhi::INPUT_PER_VERTEX_DATA, 0},
      {"KINDLIFE", 0, rhi::DXGI_FORMAT_R32G32_UINT, 0, 32, rhi::INPUT_PER_VERTEX_DATA, 0}};
  ComPtr<rhi::InputLayout> layout;
  ASSERT_EQ(device->CreateInputLayout(elements, 4, pd.pIAInputSignature, pd.IAInputSignatureSize,
                                      layout.GetAddressOf()),
            rhi::S_OK);
  rhi::QUERY_DESC qd{rhi::QUERY_SO_STATISTICS, 0};
  ComPtr<rhi::Query> query;
  ASSERT_EQ(device->CreateQuery(&qd, query.GetAddressOf()), rhi::S_OK);
  renderer::ParticleCountModel model(rule);
  context->IASetInputLayout(layout.Get());
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_POINTLIST);
  UINT stride = sizeof(Particle), zero = 0;
  int current = 0;
  for (uint32_t frame = 1; frame <= 12; ++frame) {
    effect->GetVariableByName("Frame")->AsScalar()->SetInt(int(frame));
    rhi::Buffer* in = frame == 1 ? init.Get() : buffers[current].Get();
    rhi::Buffer* out = buffers[frame == 1 ? 0 : 1 - current].Get();
    context->IASetVertexBuffers(0, 1, &in, &stride, &zero);
    ASSERT_EQ(update->Apply(0, context.Get()), rhi::S_OK);
    context->SOSetTargets(1, &out, &zero);
    context->Begin(query.Get());
    if (frame == 1)
      context->Draw(rule.emitters, 0);
    else
      context->DrawAuto();
    context->End(query.Get());
    context->SOSetTargets(0, nullptr, nullptr);
    current = frame == 1 ? 0 : 1 - current;
    auto stats = WaitForData<rhi::QUERY_DATA_SO_STATISTICS>(query.Get());
    EXPECT_EQ(stats.NumPrimitivesWritten, model.Step()) << "update " << frame;
  }

  // Draw them (billboards, smoke PS, alpha blend) without validation messages.
  const uint8_t white[4] = {255, 255, 255, 255};
  rhi::TEXTURE2D_DESC td{1, 1, 1, 1, rhi::DXGI_FORMAT_R8G8B8A8_UNORM, {1, 0}, rhi::USAGE_IMMUTABLE,
                         rhi::BIND_SHADER_RESOURCE, 0, 0};
  rhi::SUBRESOURCE_DATA data{white, 4, 0};
  ComPtr<rhi::Texture2D> puff;
  ComPtr<rhi::ShaderResourceView> puffView;
  ASSERT_EQ(device->CreateTexture2D(&td, &data, puff.GetAddressOf()), rhi::S_OK);
  ASSERT_EQ(device->CreateShaderResourceView(puff.Get(), nullptr, puffView.GetAddressOf()), rhi::S_OK);
  effect->GetVariableByName("Puff")->AsShaderResource()->SetResource(puffView.Get());
  const float viewProj[16] = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.1f, 0.5f, 0, 0, 0, 1};
  effect->GetVariableByName("ViewProj")->AsMatrix()->SetMatrix(viewProj);
  const float eye[4] = {0, 0, -5, 0};
  effect->GetVariableByName("Eye")->AsVector()->SetFloatVector(eye);
  effect->GetVariableByName("Size")->AsScalar()->SetFloat(0.2f);
  Target target = MakeRenderTarget(32, 32);
  const float black[4] = {0, 0, 0, 1};
  context->ClearRenderTargetView(target.rtv.Get(), black);
  rhi::RenderTargetView* rtv = target.rtv.Get();
  context->OMSetRenderTargets(1, &rtv, nullptr);
  SetViewport(32, 32);
  rhi::Buffer* in = buffers[current].Get();
  context->IASetVertexBuffers(0, 1, &in, &stride, &zero);
  ASSERT_EQ(effect->GetTechniqueByName("Alpha")->GetPassByName("Transparency")->Apply(0, context.Get()), rhi::S_OK);
  context->DrawAuto();
  std::vector<uint8_t> pixels = ReadTexture(target.texture.Get());
  int lit = 0;
  for (UINT i = 0; i < 32 * 32; ++i) lit += pixels[i * 4] > 0;
  EXPECT_GT(lit, 0);
}

// WBOIT: one translucent red layer (a = 0.5) composed over black gives half red.
TEST_F(EffectTest, WboitPassesComposeOneLayer) {
  auto effect = Load(kShaderDir + "/oit.fx");
  ASSERT_TRUE(effect);
  auto makeTarget = [&](rhi::DXGI_FORMAT format, ComPtr<rhi::Texture2D>& tex, ComPtr<rhi::RenderTargetView>& rtv,
                        ComPtr<rhi::ShaderResourceView>& srv) {
    rhi::TEXTURE2D_DESC d{8, 8, 1, 1, format, {1, 0}, rhi::USAGE_DEFAULT,
                          rhi::BIND_RENDER_TARGET | rhi::BIND_SHADER_RESOURCE, 0, 0};
    ASSERT_EQ(device->CreateTexture2D(&d, nullptr, tex.GetAddressOf()), rhi::S_OK);
    ASSERT_EQ(device->CreateRenderTargetView(tex.Get(), nullptr, rtv.GetAddressOf()), rhi::S_OK);
    ASSERT_EQ(device->CreateShaderResourceView(tex.Get(), nullptr, srv.GetAddressOf()), rhi::S_OK);
  };
  ComPtr<rhi::Texture2D> accum, reveal;
  ComPtr<rhi::RenderTargetView> accumRtv, revealRtv;
  ComPtr<rhi::ShaderResourceView> accumSrv, revealSrv;
  makeTarget(rhi::DXGI_FORMAT_R16G16B16A16_FLOAT, accum, accumRtv, accumSrv);
  makeTarget(rhi::DXGI_FORMAT_R8_UNORM, reveal, revealRtv, revealSrv);
  Target frame = MakeRenderTarget(8, 8);
  const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 0, 0, 0}, black[4] = {0, 0, 0, 1};
  context->ClearRenderTargetView(accumRtv.Get(), zero);
  context->ClearRenderTargetView(revealRtv.Get(), one);
  context->ClearRenderTargetView(frame.rtv.Get(), black);
  SetViewport(8, 8);

  // A quad in front of everything (z = 0.5), drawn as a triangle strip.
  const float quad[] = {-1, -1, 0.5f, -1, 1, 0.5f, 1, -1, 0.5f, 1, 1, 0.5f};
  auto vb = MakeBuffer(rhi::BIND_VERTEX_BUFFER, quad, sizeof quad);
  fx::EffectTechnique* wboit = effect->GetTechniqueByName("Wboit");
  fx::PASS_DESC pd;
  wboit->GetPassByName("Transparency")->GetDesc(&pd);
  const rhi::INPUT_ELEMENT_DESC element{"POSITION", 0, rhi::DXGI_FORMAT_R32G32B32_FLOAT, 0, 0,
                                        rhi::INPUT_PER_VERTEX_DATA, 0};
  ComPtr<rhi::InputLayout> layout;
  ASSERT_EQ(device->CreateInputLayout(&element, 1, pd.pIAInputSignature, pd.IAInputSignatureSize,
                                      layout.GetAddressOf()),
            rhi::S_OK);
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  effect->GetVariableByName("WorldViewProj")->AsMatrix()->SetMatrix(identity);
  rhi::RenderTargetView* targets[2] = {accumRtv.Get(), revealRtv.Get()};
  context->OMSetRenderTargets(2, targets, nullptr);
  UINT stride = 12, offset = 0;
  rhi::Buffer* vbp = vb.Get();
  context->IASetInputLayout(layout.Get());
  context->IASetVertexBuffers(0, 1, &vbp, &stride, &offset);
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLESTRIP);
  ASSERT_EQ(wboit->GetPassByName("Transparency")->Apply(0, context.Get()), rhi::S_OK);
  context->Draw(4, 0);

  rhi::RenderTargetView* frameRtv = frame.rtv.Get();
  context->OMSetRenderTargets(1, &frameRtv, nullptr);
  effect->GetVariableByName("Accum")->AsShaderResource()->SetResource(accumSrv.Get());
  effect->GetVariableByName("Revealage")->AsShaderResource()->SetResource(revealSrv.Get());
  context->IASetPrimitiveTopology(rhi::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ASSERT_EQ(wboit->GetPassByName("Compose")->Apply(0, context.Get()), rhi::S_OK);
  context->Draw(3, 0);
  std::vector<uint8_t> pixels = ReadTexture(frame.texture.Get());
  uint32_t p = Pixel(pixels, 8, 3, 3);
  EXPECT_NEAR(int(p & 0xFF), 128, 2);
  EXPECT_EQ((p >> 8) & 0xFF, 0u);
}

// Texture3D and RWTexture3D variables: one compute pass writes every texel of a volume
// through a UAV, the next samples each texel's centre through an SRV of it.
TEST_F(EffectTest, VolumeWrittenThroughRWTexture3DIsSampledThroughTexture3D) {
  auto effect = FromMemory(R"(
RWTexture3D<float> Volume;
Texture3D<float> VolumeRead;
SamplerState Point { Filter = MIN_MAG_MIP_POINT; };
RWStructuredBuffer<float> Out;
[numthreads(2, 2, 2)] void Write(uint3 id : SV_DispatchThreadID) { Volume[id] = id.x + 2 * id.y + 4 * id.z; }
[numthreads(8, 1, 1)] void Read(uint i : SV_DispatchThreadID) {
  float3 uvw = (float3(i % 2, (i / 2) % 2, i / 4) + 0.5) / 2;
  Out[i] = VolumeRead.SampleLevel(Point, uvw, 0);
}
technique11 T {
  pass Write { SetComputeShader(CompileShader(cs_5_0, Write())); }
  pass Read { SetComputeShader(CompileShader(cs_5_0, Read())); }
}
)");
  ASSERT_TRUE(effect);
  rhi::TEXTURE3D_DESC desc{2, 2, 2, 1, rhi::DXGI_FORMAT_R32_FLOAT, rhi::USAGE_DEFAULT,
                           rhi::BIND_UNORDERED_ACCESS | rhi::BIND_SHADER_RESOURCE, 0, 0};
  ComPtr<rhi::Texture3D> volume;
  ASSERT_EQ(device->CreateTexture3D(&desc, nullptr, volume.GetAddressOf()), rhi::S_OK);
  ComPtr<rhi::UnorderedAccessView> uav;
  ComPtr<rhi::ShaderResourceView> srv;
  ASSERT_EQ(device->CreateUnorderedAccessView(volume.Get(), nullptr, uav.GetAddressOf()), rhi::S_OK);
  ASSERT_EQ(device->CreateShaderResourceView(volume.Get(), nullptr, srv.GetAddressOf()), rhi::S_OK);
  Rw out = MakeRw(8);
  ASSERT_EQ(effect->GetVariableByName("Volume")->AsUnorderedAccessView()->SetUnorderedAccessView(uav.Get()), rhi::S_OK);
  ASSERT_EQ(effect->GetVariableByName("VolumeRead")->AsShaderResource()->SetResource(srv.Get()), rhi::S_OK);
  ASSERT_EQ(effect->GetVariableByName("Out")->AsUnorderedAccessView()->SetUnorderedAccessView(out.uav.Get()), rhi::S_OK);
  fx::EffectTechnique* technique = effect->GetTechniqueByIndex(0);
  ASSERT_EQ(technique->GetPassByName("Write")->Apply(0, context.Get()), rhi::S_OK);
  context->Dispatch(1, 1, 1);
  // The volume leaves the UAV slot before it is read (D3D11's binding hazard rule).
  rhi::UnorderedAccessView* none = nullptr;
  context->CSSetUnorderedAccessViews(0, 1, &none, nullptr);
  ASSERT_EQ(technique->GetPassByName("Read")->Apply(0, context.Get()), rhi::S_OK);
  context->Dispatch(1, 1, 1);
  const std::vector<float> got = ReadBufferAs<float>(out.buffer.Get());
  for (int i = 0; i < 8; ++i) EXPECT_EQ(got[i], float(i)) << "texel " << i;
  EXPECT_TRUE(Refusals().empty());
}

}  // namespace
}  // namespace effects_test

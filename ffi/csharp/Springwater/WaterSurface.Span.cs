// Span overloads of the per-node buffers, where the runtime has Span<T> (Mono's corlib,
// .NET Core, Godot's .NET, Unity 2021.2 and later); Unity versions before 2021.2 lack it,
// and any build can leave them out with SPRINGWATER_NO_SPAN.
#if UNITY_5_3_OR_NEWER && !UNITY_2021_2_OR_NEWER
#define SPRINGWATER_NO_SPAN
#endif
#if !SPRINGWATER_NO_SPAN
using System;
using System.Runtime.InteropServices;

namespace Springwater
{
    public sealed unsafe partial class WaterSurface
    {
        /// <summary>Every node's position, interleaved x, y, z.</summary>
        public void WritePositions(Span<float> xyz)
        {
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
                WritePositions(p, xyz.Length);
        }

        /// <summary>Every node's unit normal, interleaved x, y, z.</summary>
        public void WriteNormals(Span<float> xyz)
        {
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
                WriteNormals(p, xyz.Length);
        }

        /// <summary>Every node's refracted bottom texture coordinate, interleaved u, v.</summary>
        public void WriteRefractionUvs(SwRefraction view, Span<float> uv)
        {
            fixed (float* p = &MemoryMarshal.GetReference(uv))
                WriteRefractionUvs(view, p, uv.Length);
        }

        /// <summary>The packed vertex buffer, one SwVertex per node.</summary>
        public void WriteVertices(SwRefraction view, Span<SwVertex> vertices)
        {
            fixed (SwVertex* p = &MemoryMarshal.GetReference(vertices))
                WriteVertices(view, p, vertices.Length);
        }

        /// <summary>Copies the LOD index buffer and returns its length.</summary>
        public int WriteLodIndices(Span<uint> indices)
        {
            fixed (uint* p = &MemoryMarshal.GetReference(indices))
                return WriteLodIndices(p, indices.Length);
        }
    }
}
#endif

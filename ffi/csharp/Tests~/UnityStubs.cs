// Stand-ins for the parts of UnityEngine the sample uses, with Unity's signatures (no
// behaviour): Unity is not available here, so ffi/tests/csharp.rs compiles the package's
// sources and the sample against these, with Unity's scripting defines, to show that they
// compile. They are not run.
using System;

namespace UnityEngine
{
    public class Object
    {
        public string name { get; set; }
        public static void Destroy(Object obj) { }
    }

    public class Component : Object
    {
        public Transform transform { get { return null; } }
        public T GetComponent<T>() { return default(T); }
    }

    public class Behaviour : Component { }

    public class MonoBehaviour : Behaviour { }

    public class Transform : Component
    {
        public Vector3 position { get; set; }
        public Vector3 InverseTransformPoint(Vector3 position) { return position; }
        public Vector3 InverseTransformDirection(Vector3 direction) { return direction; }
        public Vector3 TransformDirection(Vector3 direction) { return direction; }
    }

    public sealed class Camera : Behaviour
    {
        public static Camera main { get { return null; } }
    }

    public sealed class MeshFilter : Component
    {
        public Mesh sharedMesh { get; set; }
    }

    public sealed class MeshRenderer : Component { }

    public enum ForceMode { Force = 0, Acceleration = 5, Impulse = 1, VelocityChange = 2 }

    public sealed class Rigidbody : Component
    {
        public Vector3 position { get; set; }
        public Vector3 velocity { get; set; }
        public Vector3 linearVelocity { get; set; }
        public void AddForce(Vector3 force, ForceMode mode = ForceMode.Force) { }
    }

    public static class Physics
    {
        public static Vector3 gravity { get { return new Vector3(0, -9.81f, 0); } }
    }

    public static class Time
    {
        public static float deltaTime { get { return 0; } }
    }

    public static class Mathf
    {
        public const float PI = (float)Math.PI;
        public static float Clamp(float value, float min, float max) { return value; }
    }

    public struct Vector3
    {
        public float x, y, z;
        public Vector3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public static Vector3 up { get { return new Vector3(0, 1, 0); } }
        public static Vector3 operator -(Vector3 a, Vector3 b) { return a; }
        public static Vector3 operator *(float d, Vector3 a) { return a; }
        public static Vector3 operator *(Vector3 a, float d) { return a; }
    }

    public struct Bounds
    {
        public Bounds(Vector3 center, Vector3 size) { }
    }

    public enum MeshTopology { Triangles = 0, Quads = 2, Lines = 3, LineStrip = 4, Points = 5 }

    [AttributeUsage(AttributeTargets.Class, AllowMultiple = true)]
    public sealed class RequireComponent : Attribute
    {
        public RequireComponent(Type requiredComponent, Type requiredComponent2) { }
    }

    public sealed class TooltipAttribute : Attribute
    {
        public TooltipAttribute(string tooltip) { }
    }

    public sealed class Mesh : Object
    {
        public Rendering.IndexFormat indexFormat { get; set; }
        public int subMeshCount { get; set; }
        public Bounds bounds { get; set; }

        public void SetVertexBufferParams(int vertexCount, params Rendering.VertexAttributeDescriptor[] attributes) { }

        public void SetVertexBufferData<T>(T[] data, int dataStart, int meshBufferStart, int count, int stream = 0,
            Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct { }

        public void SetIndexBufferParams(int indexCount, Rendering.IndexFormat format) { }

        public void SetIndexBufferData<T>(T[] data, int dataStart, int meshBufferStart, int count,
            Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) where T : struct { }

        public void SetSubMesh(int index, Rendering.SubMeshDescriptor desc,
            Rendering.MeshUpdateFlags flags = Rendering.MeshUpdateFlags.Default) { }
    }
}

namespace UnityEngine.Rendering
{
    public enum IndexFormat { UInt16 = 0, UInt32 = 1 }

    public enum VertexAttribute { Position = 0, Normal, Tangent, Color, TexCoord0, TexCoord1 }

    public enum VertexAttributeFormat { Float32 = 0, Float16, UNorm8, SNorm8 }

    [Flags]
    public enum MeshUpdateFlags
    {
        Default = 0,
        DontValidateIndices = 1,
        DontResetBoneBounds = 2,
        DontNotifyMeshUsers = 4,
        DontRecalculateBounds = 8,
    }

    public struct VertexAttributeDescriptor
    {
        public VertexAttributeDescriptor(VertexAttribute attribute = VertexAttribute.Position,
            VertexAttributeFormat format = VertexAttributeFormat.Float32, int dimension = 3, int stream = 0) { }
    }

    public struct SubMeshDescriptor
    {
        public SubMeshDescriptor(int indexStart, int indexCount, MeshTopology topology = MeshTopology.Triangles) { }
    }
}

using System;
using System.Runtime.InteropServices;
using System.Text;

namespace Springwater
{
    /// <summary>
    /// A call the library refused. <see cref="Exception.Message"/> is the library's own
    /// message (sw_last_error), <see cref="Status"/> its SW_ERROR_* code. A refused call
    /// changed nothing.
    /// </summary>
    public sealed class SpringwaterException : Exception
    {
        /// <summary>The status the call returned: one of Native.SW_ERROR_*.</summary>
        public int Status { get; private set; }

        /// <summary>The status's name, such as "SW_ERROR_INVALID_ARGUMENT".</summary>
        public string StatusName
        {
            get { return Marshal.PtrToStringAnsi(Native.sw_status_name(Status)); }
        }

        public SpringwaterException(int status, string message)
            : base(message)
        {
            Status = status;
        }

        /// <summary>Throws for a failed status, with this thread's last error message.</summary>
        internal static void Check(int status)
        {
            if (status != Native.SW_OK)
                throw new SpringwaterException(status, LastError());
        }

        /// <summary>This thread's last error message from the library.</summary>
        public static unsafe string LastError()
        {
            int size = (int)Native.sw_last_error(null, UIntPtr.Zero);
            if (size <= 1)
                return "";
            var bytes = new byte[size];
            fixed (byte* p = bytes)
                Native.sw_last_error(p, (UIntPtr)bytes.Length);
            return Encoding.UTF8.GetString(bytes, 0, size - 1);
        }
    }

    /// <summary>Owns a live native handle (a surface's or a hull's).</summary>
    internal abstract class OwnedHandle : SafeHandle
    {
        protected OwnedHandle(IntPtr owned)
            : base(IntPtr.Zero, true)
        {
            SetHandle(owned);
        }

        public override bool IsInvalid
        {
            get { return handle == IntPtr.Zero; }
        }
    }

    /// <summary>Owns a live surface handle; releasing it destroys the surface.</summary>
    internal sealed class SurfaceHandle : OwnedHandle
    {
        internal SurfaceHandle(IntPtr surface)
            : base(surface) { }

        protected override bool ReleaseHandle()
        {
            Native.sw_surface_destroy(handle);
            return true;
        }
    }

    /// <summary>Owns a live hull handle; releasing it destroys the hull (its bodies keep their mesh).</summary>
    internal sealed class HullHandle : OwnedHandle
    {
        internal HullHandle(IntPtr hull)
            : base(hull) { }

        protected override bool ReleaseHandle()
        {
            Native.sw_hull_destroy(handle);
            return true;
        }
    }

    /// <summary>
    /// A native call in progress: holds a reference on the handle so that a Dispose on
    /// another thread cannot destroy the surface (or hull) under the call. After Dispose it hands the
    /// destroyed handle's value to the library, which refuses it (handles are never reused)
    /// with SW_ERROR_INVALID_HANDLE and its own message.
    /// </summary>
    internal struct Borrow : IDisposable
    {
        readonly OwnedHandle owner;
        readonly bool held;
        public readonly IntPtr Ptr;

        internal Borrow(OwnedHandle owner, IntPtr raw)
        {
            this.owner = owner;
            held = false;
            Ptr = raw;
            if (owner.IsClosed)
                return;
            try
            {
                owner.DangerousAddRef(ref held);
            }
            catch (ObjectDisposedException)
            {
                // Disposed since the check: the library refuses the stale handle.
            }
        }

        public void Dispose()
        {
            if (held)
                owner.DangerousRelease();
        }
    }
}
